#!/usr/bin/env python3
"""Tables (markdown) and the log-log plot (SVG through gnuplot) of the work-precision runs.

    work_precision_report.py RESULTS.jsonl PLOT.svg > table.md

One table per model: a row per method, a column per rtol, each cell "achieved error /
right-hand-side evaluations / CPU ms" (process CPU time: both engines are single-threaded, and
wall time on a shared machine measures the other jobs too). Fixed-step peers (runs with a "step"
instead of an rtol: MuJoCo's RK4) get a second table per model: for each run of the default
`dop853`, the fixed step at which the peer reaches the same error, with its evaluations and CPU
time (log-log interpolation between the two steps around that error). Models with SciPy peers get
a third: at the error of each default run, SciPy DOP853's evaluations (interpolated the same way
between the two rtols around that error) and the fastest SciPy method's CPU and wall time, as
ratios to ours ("> x" where ours is more accurate than every run of a SciPy method: its most
accurate run is the bound). The plot is the double pendulum's: achieved error on x, CPU time on y, one line
per method.
"""

import json
import math
import subprocess
import sys
from collections import defaultdict


DEFAULT = "dop853"


def at_error(runs, error, keys=("step", "rhs_evals", "cpu_s"), coarse_first=None):
    """`keys` of the runs interpolated (log-log) at `error` between two consecutive runs (ordered
    coarse to fine by `coarse_first`, default: the fixed step, largest first) whose errors bracket
    it, or None when no two do."""
    runs = sorted(runs, key=coarse_first or (lambda r: -r["step"]))
    for a, b in zip(runs, runs[1:]):
        if not (math.isfinite(a["error"]) and b["error"] > 0):
            continue
        if b["error"] <= error <= a["error"] and a["error"] > b["error"]:
            w = math.log(a["error"] / error) / math.log(a["error"] / b["error"])
            return tuple(math.exp((1 - w) * math.log(a[k]) + w * math.log(b[k])) for k in keys)
    return None


def print_scipy_targets(model, methods):
    """At the error of each default run: SciPy DOP853's evaluations and the fastest SciPy
    method's CPU and wall time, each as a ratio to ours (issue targets: evaluations ratio ≥ 1,
    time ratio ≥ 50)."""
    scipy = {m: list(runs.values()) for m, runs in methods.items() if m.startswith("scipy:")}
    if not scipy:
        return
    by_rtol = lambda r: -r["rtol"]  # noqa: E731  (loose to tight)
    print(f"\n{DEFAULT} on {model} against SciPy at equal achieved error (log-log interpolation "
          "between the two SciPy runs whose errors bracket ours):\n")
    print(f"| rtol | `{DEFAULT}`: error / evals / CPU ms / wall ms | scipy:DOP853 evals | "
          "evals ratio | fastest SciPy: CPU ms / wall ms | CPU ratio | wall ratio |")
    print("|---|---|---|---|---|---|---|")
    for rtol, r in sorted(methods.get(DEFAULT, {}).items(), reverse=True):
        ours = (f"{r['error']:.1e} / {r['rhs_evals']} / {1e3 * r['cpu_s']:.1f} / "
                f"{1e3 * r['wall_s']:.1f}")
        # Below the error of every run of a SciPy method, its most accurate run (still less
        # accurate than ours) gives a lower bound, marked ">".
        def peer(runs, keys):
            t = at_error(runs, r["error"], keys, by_rtol)
            if t is not None:
                return t, ""
            done = [p for p in runs if math.isfinite(p["error"])]
            if done and r["error"] < min(p["error"] for p in done):
                best_run = min(done, key=lambda p: p["error"])
                return tuple(best_run[k] for k in keys), ">"
            return None, ""
        dop, mark = peer(scipy.get("scipy:DOP853", []), ("rhs_evals",))
        dop_cells = ("not bracketed | —" if dop is None else
                     f"{mark}{dop[0]:.0f} | {mark}{dop[0] / r['rhs_evals']:.2f}×")
        best = None
        for name, runs in scipy.items():
            t, mark = peer(runs, ("cpu_s", "wall_s"))
            if t is not None and (best is None or t[0] < best[1][0]):
                best = (name, t, mark)
        if best is None:
            time_cells = "not bracketed | — | —"
        else:
            name, (cpu, wall), mark = best
            time_cells = (f"{name}: {mark}{1e3 * cpu:.0f} / {mark}{1e3 * wall:.0f} | "
                          f"{mark}{cpu / r['cpu_s']:.0f}× | {mark}{wall / r['wall_s']:.0f}×")
        print(f"| {rtol:.0e} | {ours} | {dop_cells} | {time_cells} |")


def print_equal_error(model, method, runs, ours):
    """The fixed-step peer at the error of each run of the default method."""
    sweep = ", ".join(f"h {r['step']:.3g}: {r['error']:.1e}"
                      for r in sorted(runs, key=lambda r: -r["step"]))
    print(f"\n{method} on {model} at the error of each `{DEFAULT}` run (fixed step h; {sweep}):\n")
    print(f"| rtol | `{DEFAULT}`: error / evals / CPU ms | " + method + ": h / evals / CPU ms "
          "| evals ratio | CPU ratio |")
    print("|---|---|---|---|---|")
    for rtol, r in sorted(ours.items(), reverse=True):
        peer = at_error(runs, r["error"])
        ours_cell = f"{r['error']:.1e} / {r['rhs_evals']} / {1e3 * r['cpu_s']:.1f}"
        if peer is None:
            print(f"| {rtol:.0e} | {ours_cell} | not bracketed | — | — |")
            continue
        h, evals, cpu = peer
        print(f"| {rtol:.0e} | {ours_cell} | {h:.2g} / {evals:.0f} / {1e3 * cpu:.1f} "
              f"| {evals / r['rhs_evals']:.1f}× | {cpu / r['cpu_s']:.1f}× |")


def main():
    rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
    plot = sys.argv[2] if len(sys.argv) > 2 else None
    by_model = defaultdict(lambda: defaultdict(dict))
    fixed = defaultdict(lambda: defaultdict(list))  # model -> method -> runs, by step
    for r in rows:
        if r.get("step") is not None:
            fixed[r["model"]][r["method"]].append(r)
        else:
            by_model[r["model"]][r["method"]][r["rtol"]] = r
    for model, methods in by_model.items():
        rtols = sorted({rt for m in methods.values() for rt in m}, reverse=True)
        print(f"\n#### {model}\n")
        print("| method | " + " | ".join(f"rtol {rt:.0e}" for rt in rtols) + " |")
        print("|---|" + "---|" * len(rtols))
        for method, runs in methods.items():
            label = f"{method} (default)" if method == DEFAULT else method
            cells = []
            for rt in rtols:
                r = runs.get(rt)
                cells.append("—" if r is None else
                             f"{r['error']:.1e} / {r['rhs_evals']} / {1e3 * r['cpu_s']:.1f}")
            print(f"| {label} | " + " | ".join(cells) + " |")
        for method, runs in fixed.get(model, {}).items():
            print_equal_error(model, method, runs, methods.get(DEFAULT, {}))
        print_scipy_targets(model, methods)
    if plot and "double_pendulum" in by_model:
        data, plots = [], []
        lines = list(by_model["double_pendulum"].items())
        lines += [(m, dict(enumerate(runs))) for m, runs in fixed["double_pendulum"].items()]
        for method, runs in lines:
            pts = [(r["error"], r["cpu_s"]) for r in runs.values()
                   if math.isfinite(r["error"]) and r["error"] > 0]
            data.append("\n".join(f"{e} {w}" for e, w in sorted(pts)))
            plots.append(f"'-' using 1:2 with linespoints title '{method}'")
        script = ("set terminal svg size 800,560 dynamic font 'sans,11'\n"
                  f"set output '{plot}'\nset logscale xy\nset format x '10^{{%L}}'\n"
                  "set format y '10^{%L}'\nset xlabel 'achieved error (max |θ − θ_ref|)'\n"
                  "set ylabel 'CPU time (s)'\nset key outside right\nset grid\n"
                  "set title 'Double pendulum (examples/double_pendulum.yaml), 10 s: work-precision'\n"
                  "plot " + ", ".join(plots) + "\n" + "\ne\n".join(data) + "\ne\n")
        subprocess.run(["gnuplot"], input=script.encode(), check=True)


if __name__ == "__main__":
    main()
