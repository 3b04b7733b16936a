#!/usr/bin/env python3
"""Tables (markdown) and the log-log plot (SVG through gnuplot) of the work-precision runs.

    work_precision_report.py RESULTS.jsonl PLOT.svg > table.md

One table per model: a row per method, a column per rtol, each cell "achieved error /
right-hand-side evaluations / CPU ms" (process CPU time: both engines are single-threaded, and
wall time on a shared machine measures the other jobs too). The plot is the double pendulum's:
achieved error on x, CPU time on y, one line per method.
"""

import json
import math
import subprocess
import sys
from collections import defaultdict


def main():
    rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
    plot = sys.argv[2] if len(sys.argv) > 2 else None
    by_model = defaultdict(lambda: defaultdict(dict))
    for r in rows:
        by_model[r["model"]][r["method"]][r["rtol"]] = r
    for model, methods in by_model.items():
        rtols = sorted({rt for m in methods.values() for rt in m}, reverse=True)
        print(f"\n#### {model}\n")
        print("| method | " + " | ".join(f"rtol {rt:.0e}" for rt in rtols) + " |")
        print("|---|" + "---|" * len(rtols))
        for method, runs in methods.items():
            label = "arkode (default)" if method == "arkode" else method
            cells = []
            for rt in rtols:
                r = runs.get(rt)
                cells.append("—" if r is None else
                             f"{r['error']:.1e} / {r['rhs_evals']} / {1e3 * r['cpu_s']:.1f}")
            print(f"| {label} | " + " | ".join(cells) + " |")
    if plot and "double_pendulum" in by_model:
        data, plots = [], []
        for i, (method, runs) in enumerate(by_model["double_pendulum"].items()):
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
