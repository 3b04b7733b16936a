#!/usr/bin/python3
"""Linearisation of the N-link pendulum: lagrange against SymPy mechanics in one run (issue 21).

The peer is SymPy's LagrangesMethod.linearize (bench/sympy_lagrange.py builds the same pendulum:
per-link masses and lengths, absolute angles), A evaluated at the benchmark state (the angles
of bench/n_link_pendulum.hpp, rates 0) with the parameter values in the operating point. lagrange
is bench_linearize (bench/bench_linearize.cpp): derive + compile + differentiate + linearize of
the same model, the exact Jacobian per call, and central finite differences through the forward
call. The two A matrices are compared, so both are the same physics.

    /usr/bin/python3 bench/linearize_vs_sympy.py --bench build/bench/bench_linearize [--n 2 3 5 10]
"""

import argparse
import json
import pathlib
import subprocess
import sys
import time

import numpy as np
from sympy.physics import mechanics as me

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import sympy_lagrange as peer  # noqa: E402


def sympy_linearize(n):
    """(A, seconds from the model to A, seconds of linearize alone) with SymPy mechanics."""
    lm, q, u, params, setup, derive_seconds, _ = peer.derive(n)
    t0 = time.perf_counter()
    op = {qi: peer.initial_angle(k) for k, qi in enumerate(q, start=1)}
    op.update({ui: 0.0 for ui in u})
    op.update(dict(zip(params, peer.parameter_values(n))))
    # The accelerations at the operating point belong to it (SymPy's linearisation of
    # M(q) q̈ − f = 0 keeps M'(q) q̈): q̈ = M⁻¹ f there, not 0 (the state is not an equilibrium).
    M = np.array(me.msubs(lm.mass_matrix, op).evalf(), dtype=float)
    f = np.array(me.msubs(lm.forcing, op).evalf(), dtype=float).reshape(-1)
    op.update({ui.diff(me.dynamicsymbols._t): a for ui, a in zip(u, np.linalg.solve(M, f))})
    A, _, _ = lm.linearize(q_ind=q, qd_ind=u, op_point=op, A_and_B=True)
    A = np.array(A.evalf(), dtype=float)
    seconds = time.perf_counter() - t0
    return A, setup + derive_seconds + seconds, seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bench", default="build/bench/bench_linearize", help="bench_linearize binary")
    ap.add_argument("--n", type=int, nargs="*", default=list(range(2, 11)), help="link counts")
    args = ap.parse_args()
    print("| N | SymPy: model → A [s] | SymPy linearize alone [s] | lagrange: model → A [s] | ratio "
          "| exact Jacobian [µs] | FD through forward [µs] | FD / exact | ‖A − A_SymPy‖_max / ‖A‖_max "
          "| FD vs exact |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n in args.n:
        out = subprocess.run([args.bench, "pendulum", str(n)], check=True, capture_output=True,
                             text=True).stdout
        ours = json.loads(out)
        A = np.array(ours["A"]).reshape(2 * n, 2 * n)
        A_sympy, sympy_total, sympy_linearize_only = sympy_linearize(n)
        difference = np.abs(A - A_sympy).max() / np.abs(A).max()
        print(f"| {n} | {sympy_total:.3g} | {sympy_linearize_only:.3g} | {ours['first_A_s']:.3g} | "
              f"{sympy_total / ours['first_A_s']:.0f}× | {ours['jacobian_us']:.3g} | {ours['fd_us']:.3g} | "
              f"{ours['fd_us'] / ours['jacobian_us']:.2g} | {difference:.1e} | {ours['fd_difference']:.1e} |",
              flush=True)


if __name__ == "__main__":
    main()
