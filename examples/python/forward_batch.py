"""Evaluate the double pendulum's accelerations on a grid of states in one call.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/forward_batch.py
"""

import pathlib
import time

import numpy as np

import lagrange

EXAMPLES = pathlib.Path(__file__).resolve().parents[1]
model = lagrange.load(str(EXAMPLES / "double_pendulum.yaml"))

theta = np.linspace(-np.pi, np.pi, 101)
T1, T2 = np.meshgrid(theta, theta)
Q = np.column_stack([T1.ravel(), T2.ravel()])
V = np.zeros_like(Q)

start = time.perf_counter()
A = model.forward_batch(Q, V)
seconds = time.perf_counter() - start
print(f"{len(Q)} states in {seconds * 1e3:.2f} ms ({seconds / len(Q) * 1e9:.0f} ns per state)")
# At rest the accelerations vanish only where both links hang or stand straight.
rest = np.all(np.abs(A) < 1e-9, axis=1)
print("equilibria on the grid:", [tuple(np.round(q, 3)) for q in Q[rest]])
