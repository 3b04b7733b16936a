"""Per-call cost of lagrange's forward dynamics from Python (docs/python.md).

For each model: the C++ loop over Dynamics::forward (forward_batch over many states: no Python in
the loop, so its time per state is the C++ call), m.forward called once per state from Python,
and the difference, the binding's overhead per call.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_forward.py
"""

import pathlib
import time

import numpy as np

import lagrange

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"
MODELS = ["pendulum.yaml", "double_pendulum.yaml", "n_link_pendulum_5.yaml",
          "constrained_pendulum.yaml"]


def best_of(repeats, fn):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return min(times)


def measure(name, batch=100000, calls=20000):
    m = lagrange.load(str(EXAMPLES / name))
    rng = np.random.default_rng(0)
    q0, v0 = m.initial_state
    Q = q0 + 0.1 * rng.standard_normal((batch, len(q0)))
    V = v0 + 0.1 * rng.standard_normal((batch, len(v0)))
    per_state = best_of(5, lambda: m.forward_batch(Q, V)) / batch
    rows = [(Q[i], V[i]) for i in range(calls)]

    def loop():
        for q, v in rows:
            m.forward(q, v)

    per_call = best_of(5, loop) / calls
    return len(q0), per_state, per_call


print("| model | nq | C++ call (forward_batch per state) | m.forward per call | overhead |")
print("|---|---|---|---|---|")
for name in MODELS:
    nq, cpp, py = measure(name)
    print(f"| {name} | {nq} | {cpp * 1e9:.0f} ns | {py * 1e9:.0f} ns | {(py - cpp) * 1e9:.0f} ns |")
