"""lagrange from Python against sympy.physics.mechanics on the same N-link pendulum (issue 23).

The peer is the usual SymPy route: LagrangesMethod, then lambdify(cse=True) of the mass matrix M
and forcing f, then numpy.linalg.solve per state (bench/sympy_lagrange.py builds it). lagrange
reads the same pendulum (per-link masses and lengths as parameters, absolute angles) from YAML
text. Per state: m.forward called from Python, and forward_batch (the C++ loop) over many states.
The accelerations of both are compared at the benchmark state, so the two are the same physics.

    PYTHONPATH=build/python /usr/bin/python3 bench/python_vs_sympy.py [--max-n 8]
"""

import argparse
import pathlib
import sys
import time

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
import sympy_lagrange as peer  # noqa: E402  (the SymPy side, shared with bench/run.sh)

import lagrange  # noqa: E402


def pendulum_yaml(n):
    """The N-link pendulum of sympy_lagrange.build_lagrangian in the model language."""
    masses = ", ".join(f"m{k}: {peer.per_link_mass(k)!r}" for k in range(1, n + 1))
    lengths = ", ".join(f"l{k}: {peer.per_link_length(k)!r}" for k in range(1, n + 1))
    lines = [f"name: {n}-link pendulum (SymPy's)",
             f"parameters: {{{masses}, {lengths}, g: {peer.GRAVITY!r}}}", "coordinates:"]
    lines += [f"  th{k}: {{initial: {peer.initial_angle(k)!r}, rate: {0.1 * k!r}}}"
              for k in range(1, n + 1)]
    lines.append("points:")
    for k in range(1, n + 1):
        before = f"p{k - 1} + " if k > 1 else ""
        lines.append(f"  p{k}: {before}[l{k}*sin(th{k}), -l{k}*cos(th{k}), 0]")
    lines.append("particles: {" + ", ".join(f"p{k}: m{k}" for k in range(1, n + 1)) + "}")
    lines.append("gravity: [0, -g, 0]")
    return "\n".join(lines) + "\n"


def best_per_call(fn, calls, repeats=5):
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        for _ in range(calls):
            fn()
        best = min(best, time.perf_counter() - start)
    return best / calls


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--max-n", type=int, default=5, help="largest N (SymPy derives slowly)")
    args = parser.parse_args()
    print("| N | SymPy derive | lagrange load (derive + compile) | SymPy lambdify + solve per "
          "state | m.forward per state | forward_batch per state | max abs Δa |")
    print("|---|---|---|---|---|---|---|")
    for n in [k for k in (2, 5, 8, 10) if k <= args.max_n]:
        lm, q, u, params, _, derive_s, _ = peer.derive(n)
        sympy_us, _, _, a_sympy = peer.evaluate(n, lm, q, u, params, min_seconds=0.2)
        start = time.perf_counter()
        m = lagrange.loads(pendulum_yaml(n), label=f"pendulum{n}.yaml")
        load_s = time.perf_counter() - start
        q0 = np.array([peer.initial_angle(k) for k in range(1, n + 1)])
        v0 = np.array([0.1 * k for k in range(1, n + 1)])
        a = m.forward(q0, v0)
        worst = float(np.max(np.abs(a - np.asarray(a_sympy))))
        forward_us = 1e6 * best_per_call(lambda: m.forward(q0, v0), 20000)
        rng = np.random.default_rng(0)
        Q = q0 + 0.1 * rng.standard_normal((100000, n))
        V = v0 + 0.1 * rng.standard_normal((100000, n))
        batch_us = 1e6 * best_per_call(lambda: m.forward_batch(Q, V), 1, repeats=5) / len(Q)
        print(f"| {n} | {derive_s:.2f} s | {load_s:.3f} s | {sympy_us:.1f} µs | {forward_us:.2f} µs "
              f"({sympy_us / forward_us:.0f}× faster) | {batch_us:.3f} µs "
              f"({sympy_us / batch_us:.0f}× faster) | {worst:.1e} |")


if __name__ == "__main__":
    main()
