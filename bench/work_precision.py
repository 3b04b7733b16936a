#!/usr/bin/env python3
"""SciPy peers of bench/work_precision.cpp: solve_ivp RK45, DOP853 and LSODA on the equations
SymPy derives (sympy.physics.mechanics LagrangesMethod), lambdified with cse=True, for the double
pendulum (10 s) and the N = 10 chain (5 s) at rtol 1e-4 ... 1e-10 (atol = rtol / 100). Errors are
against the reference the C++ program wrote (arkode:verner65 at rtol 1e-13), on the same samples
(every 0.1 s). One JSON line per run, like work_precision.

    work_precision.py REFERENCE_DIR
"""

import json
import math
import os
import sys
import time

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from sympy.physics import mechanics as me

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sympy_lagrange as family  # noqa: E402  (the N-link family's Lagrangian and values)


def peer_rhs(n, masses, lengths):
    """f(t, y) for y = (θ, θ̇) from LagrangesMethod, M and forcing lambdified with cse=True."""
    L, q, u, params = family.build_lagrangian(n)
    lm = me.LagrangesMethod(L, q)
    lm.form_lagranges_equations()
    qs = sp.symbols(f"q1:{n + 1}")
    us = sp.symbols(f"u1:{n + 1}")
    subs = dict(zip(u, us))
    subs.update(zip(q, qs))
    M = me.msubs(lm.mass_matrix, subs)
    f = me.msubs(lm.forcing, subs)
    fn = sp.lambdify([qs, us, params], [M, f], modules="numpy", cse=True)
    pv = list(masses) + list(lengths) + [family.GRAVITY]

    def rhs(_t, y):
        Mv, fv = fn(y[:n], y[n:], pv)
        a = np.linalg.solve(np.asarray(Mv, dtype=float), np.asarray(fv, dtype=float).reshape(-1))
        return np.concatenate((y[n:], a))

    return rhs


def cases():
    yield "double_pendulum", 2, [1.0, 1.0], [1.0, 1.0], [1.5, 2.5], 10.0
    n = 10
    ks = range(1, n + 1)
    yield ("chain_10", n, [family.per_link_mass(k) for k in ks],
           [family.per_link_length(k) for k in ks], [family.initial_angle(k) for k in ks], 5.0)


def main():
    ref_dir = sys.argv[1] if len(sys.argv) > 1 else "."
    for name, n, masses, lengths, angles, t_end in cases():
        with open(os.path.join(ref_dir, f"reference_{name}.json")) as f:
            ref = json.load(f)
        q_ref = np.asarray(ref["q"]).reshape(-1, n)
        t_eval = np.linspace(0.0, t_end, q_ref.shape[0])
        rhs = peer_rhs(n, masses, lengths)
        y0 = np.concatenate((angles, np.zeros(n)))
        for method in ("RK45", "DOP853", "LSODA"):
            for e in range(4, 11):
                rtol = 10.0 ** -e
                # The least time of up to three runs (one when a run takes over a second), as
                # work_precision.cpp does for ours.
                wall = cpu = math.inf
                for _ in range(3):
                    w0, c0 = time.perf_counter(), time.process_time()
                    sol = solve_ivp(rhs, (0.0, t_end), y0, method=method, t_eval=t_eval,
                                    rtol=rtol, atol=rtol / 100)
                    wall = min(wall, time.perf_counter() - w0)
                    cpu = min(cpu, time.process_time() - c0)
                    if wall > 1.0:
                        break
                error = (float(np.max(np.abs(sol.y[:n].T - q_ref))) if sol.success
                         and sol.y.shape[1] == q_ref.shape[0] else float("inf"))
                print(json.dumps({"engine": "scipy", "model": name, "method": f"scipy:{method}",
                                  "ran": f"scipy:{method}", "rtol": rtol, "error": error,
                                  "rhs_evals": int(sol.nfev), "steps": None, "wall_s": wall,
                                  "cpu_s": cpu}), flush=True)


if __name__ == "__main__":
    main()
