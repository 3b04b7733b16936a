#!/usr/bin/python3
"""SymPy peer of the N-link pendulum benchmark (docs/benchmarks.md, "Peers"), run with Debian's /usr/bin/python3.

Builds the same model as bench/n_link_pendulum.cpp (planar N-link pendulum, absolute angles,
point masses at the link ends, per-link masses m_k and lengths l_k kept symbolic) with
sympy.physics.mechanics, and times

  derive: LagrangesMethod(L, q).form_lagranges_equations()  (derivation alone)
  eval:   one call of lambdify(cse=True) of the mass matrix M and forcing f, plus
          numpy.linalg.solve(M, f), at the benchmark state of bench_pendulum.

Prints one JSON object per line (machine-readable; bench/run.sh reads them):
  {"peer": "sympy", "kind": "derive", "n": N, "seconds": wall s, "cpu_seconds": s,
   "setup_seconds": s}
  {"peer": "sympy", "kind": "eval", "n": N, "us_per_call": wall us, "cpu_us_per_call": us,
   "lambdify_seconds": s, "accelerations": [...]}
Wall and process CPU time are both reported: when other jobs share the cores, CPU time is the
fairer comparison.
N = 20 takes about a minute (another run: 52 s, docs/benchmarks.md) and runs only with --with-20; N = 50 takes hours.
"""

import argparse
import json
import sys
import time
import timeit

import numpy as np
import sympy as sp
from sympy.physics import mechanics as me


# The same values as bench/n_link_pendulum.cpp (1-based link index k).
def initial_angle(k):
    return 0.5 - 0.1 * (k % 4)


def per_link_mass(k):
    return 1.0 + 0.1 * (k % 7)


def per_link_length(k):
    return 0.5 + 0.05 * (k % 5)


GRAVITY = 9.81


def build_lagrangian(n):
    """Lagrangian of the N-link pendulum from Points and Particles; returns (L, q, u, params)."""
    q = me.dynamicsymbols(f"th1:{n + 1}")
    u = [qi.diff(me.dynamicsymbols._t) for qi in q]
    m = sp.symbols(f"m1:{n + 1}")
    l = sp.symbols(f"l1:{n + 1}")
    g = sp.Symbol("g")
    frame = me.ReferenceFrame("N")
    origin = me.Point("O")
    origin.set_vel(frame, 0)
    previous = origin
    particles = []
    for k in range(n):
        p = previous.locatenew(f"P{k + 1}", l[k] * sp.sin(q[k]) * frame.x - l[k] * sp.cos(q[k]) * frame.y)
        p.set_vel(frame, p.pos_from(origin).dt(frame))
        particle = me.Particle(f"Pa{k + 1}", p, m[k])
        particle.potential_energy = m[k] * g * p.pos_from(origin).dot(frame.y)
        particles.append(particle)
        previous = p
    L = me.Lagrangian(frame, *particles)
    return L, q, u, list(m) + list(l) + [g]


def parameter_values(n):
    return ([per_link_mass(k) for k in range(1, n + 1)] + [per_link_length(k) for k in range(1, n + 1)]
            + [GRAVITY])


def derive(n):
    """Returns (lm, q, u, params, setup wall s, derive wall s, derive CPU s)."""
    t0 = time.perf_counter()
    L, q, u, params = build_lagrangian(n)
    t1, c1 = time.perf_counter(), time.process_time()
    lm = me.LagrangesMethod(L, q)
    lm.form_lagranges_equations()
    t2, c2 = time.perf_counter(), time.process_time()
    return lm, q, u, params, t1 - t0, t2 - t1, c2 - c1


def evaluate(n, lm, q, u, params, min_seconds):
    """lambdify(cse=True) of M and f, then time M, f evaluation + numpy solve per call."""
    qs = sp.symbols(f"q1:{n + 1}")
    us = sp.symbols(f"u1:{n + 1}")
    subs = dict(zip(u, us))
    subs.update(zip(q, qs))
    t0 = time.perf_counter()
    M = me.msubs(lm.mass_matrix, subs)
    f = me.msubs(lm.forcing, subs)
    fn = sp.lambdify([qs, us, params], [M, f], modules="numpy", cse=True)
    t1 = time.perf_counter()
    qv = [initial_angle(k) for k in range(1, n + 1)]
    uv = [0.1 * k for k in range(1, n + 1)]
    pv = parameter_values(n)

    def call():
        Mv, fv = fn(qv, uv, pv)
        return np.linalg.solve(np.asarray(Mv, dtype=float), np.asarray(fv, dtype=float).reshape(-1))

    a = call()
    per_call = []
    for clock in (time.perf_counter, time.process_time):
        timer = timeit.Timer(call, timer=clock)
        number, _ = timer.autorange()
        while True:
            elapsed = min(timer.repeat(repeat=3, number=number))
            if elapsed * 3 >= min_seconds or number > 1_000_000:
                break
            number *= 2
        per_call.append(1e6 * elapsed / number)
    return per_call[0], per_call[1], t1 - t0, [float(x) for x in a]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, nargs="*", default=[2, 5, 8, 10],
                    help="link counts to derive (default: 2 5 8 10)")
    ap.add_argument("--with-20", action="store_true", help="also derive N = 20 (about a minute)")
    ap.add_argument("--eval-max", type=int, default=10,
                    help="time lambdify(cse=True) evaluation for N up to this (default 10; 0: never)")
    ap.add_argument("--min-time", type=float, default=0.3, help="minimum timing per eval measurement (s)")
    args = ap.parse_args()
    ns = list(args.n) + ([20] if args.with_20 and 20 not in args.n else [])
    print(json.dumps({"peer": "sympy", "kind": "version", "sympy": sp.__version__, "numpy": np.__version__,
                      "python": sys.version.split()[0]}), flush=True)
    for n in ns:
        lm, q, u, params, setup, seconds, cpu_seconds = derive(n)
        print(json.dumps({"peer": "sympy", "kind": "derive", "n": n, "seconds": seconds,
                          "cpu_seconds": cpu_seconds, "setup_seconds": setup}), flush=True)
        if n <= args.eval_max:
            us, cpu_us, lambdify_seconds, a = evaluate(n, lm, q, u, params, args.min_time)
            print(json.dumps({"peer": "sympy", "kind": "eval", "n": n, "us_per_call": us,
                              "cpu_us_per_call": cpu_us, "lambdify_seconds": lambdify_seconds,
                              "accelerations": a}), flush=True)


if __name__ == "__main__":
    main()
