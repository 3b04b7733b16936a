#!/usr/bin/python3
"""Comparison table of one bench/run.sh run: reads DIR/{pendulum.json, chain.json,
sympy.jsonl, accelerations.txt} and prints Markdown tables with ratios and the targets."""

import json
import re
import sys
from pathlib import Path

UNIT = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}
# MuJoCo reference figures (docs/benchmarks.md, "Peers": another run on a machine of this kind;
# not measured here).
MUJOCO_US = {2: 0.85, 5: 1.8, 10: 3.4, 20: 8.2, 50: 38}


def load_benchmarks(path):
    """{(family, N): benchmark entry} from a Google Benchmark JSON file."""
    result = {}
    for b in json.loads(path.read_text())["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration" or b.get("error_occurred"):
            continue
        m = re.match(r"^(BM_\w+)/(\d+)", b["name"])
        if m:
            b["seconds"] = b["real_time"] * UNIT[b["time_unit"]]
            result[(m.group(1), int(m.group(2)))] = b
    return result


def fmt_s(s):
    if s is None:
        return "—"
    if s >= 1:
        return f"{s:.2f} s"
    if s >= 1e-3:
        return f"{s * 1e3:.1f} ms"
    return f"{s * 1e6:.0f} µs"


def fmt_ratio(r):
    return "—" if r is None else (f"{r:,.0f}×" if r >= 10 else f"{r:.1f}×")


def us_call(e, key):
    return f"{e[key]:.1f} µs" if e else "—"


def verdict(wall_ok, cpu_ok):
    if wall_ok and cpu_ok:
        return "**met**"
    if not wall_ok and not cpu_ok:
        return "**missed**"
    return "**met** (CPU), missed (wall)" if cpu_ok else "**met** (wall), missed (CPU)"


def main():
    d = Path(sys.argv[1])
    pend = load_benchmarks(d / "pendulum.json")
    chain = load_benchmarks(d / "chain.json")
    sympy_derive, sympy_eval = {}, {}
    for line in (d / "sympy.jsonl").read_text().splitlines():
        rec = json.loads(line)
        if rec.get("kind") == "derive":
            sympy_derive[rec["n"]] = rec
        elif rec.get("kind") == "eval":
            sympy_eval[rec["n"]] = rec
    ours_a = {}
    for line in (d / "accelerations.txt").read_text().splitlines():
        parts = line.split()
        ours_a[int(parts[1])] = [float(x) for x in parts[2:]]

    print("Wall = elapsed time; CPU = process CPU time. Both engines are single-threaded, so CPU time "
          "is the fairer comparison when other jobs share the cores.\n")
    print("## Derivation + compilation, N-link pendulum (per-link m_k, l_k symbolic)\n")
    print("| N | derive | compile | specialise | **total wall** | total CPU "
          "| tape instr (symbolic → specialised) | SymPy derive wall | SymPy derive CPU "
          "| **SymPy / ours** (wall, CPU) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    dc = {n: b for (f, n), b in pend.items() if f == "BM_DeriveCompile"}
    for n in sorted(dc):
        b = dc[n]
        s = sympy_derive.get(n)
        ratios = (f"{fmt_ratio(s['seconds'] / b['seconds'])}, {fmt_ratio(s['cpu_seconds'] / b['build_cpu_s'])}"
                  if s else "—")
        print(f"| {n} | {fmt_s(b['derive_s'])} | {fmt_s(b['compile_s'])} | {fmt_s(b['specialise_s'])} "
              f"| {fmt_s(b['seconds'])} | {fmt_s(b['build_cpu_s'])} | {b['instr']:.0f} → {b['instr_spec']:.0f} "
              f"| {fmt_s(s['seconds']) if s else '— (not run)'} | {fmt_s(s['cpu_seconds']) if s else '—'} "
              f"| {ratios} |")
    shared = {n: b for (f, n), b in pend.items() if f == "BM_DeriveCompileShared"}
    if shared:
        print("\nShared m, l (the model of the Peers figures), derive + compile + specialise: "
              + "; ".join(f"N = {n}: {fmt_s(b['seconds'])} wall, {fmt_s(b['build_cpu_s'])} CPU, "
                          f"{b['instr_spec']:.0f} instr" for n, b in sorted(shared.items())))

    print("\n## Forward dynamics per call, N-link pendulum\n")
    print("| N | lagrange wall | lagrange CPU | tape instr | SymPy lambdify(cse) + numpy solve, wall "
          "| SymPy CPU | **SymPy / ours** (CPU) | MuJoCo mj_forward (Peers, not this run) "
          "| max abs Δa vs SymPy |")
    print("|---|---|---|---|---|---|---|---|---|")
    fw = {n: b for (f, n), b in pend.items() if f == "BM_Forward"}
    for n in sorted(fw):
        b = fw[n]
        e = sympy_eval.get(n)
        cpu = b["cpu_time"] * UNIT[b["time_unit"]]
        ratio = e["cpu_us_per_call"] * 1e-6 / cpu if e else None
        diff = "—"
        if e and n in ours_a:
            diff = f"{max(abs(x - y) for x, y in zip(ours_a[n], e['accelerations'])):.1e}"
        print(f"| {n} | {b['seconds'] * 1e6:.2f} µs | {cpu * 1e6:.2f} µs | {b['instr_spec']:.0f} "
              f"| {us_call(e, 'us_per_call')} | {us_call(e, 'cpu_us_per_call')} "
              f"| {fmt_ratio(ratio)} | {MUJOCO_US.get(n, '—')} µs | {diff} |")

    print("\n## Forward dynamics per call, Cartesian chain (2N coordinates, N rods, KKT)\n")
    print("| links N | lagrange wall | lagrange CPU | M diagonal | derive + compile (wall) |")
    print("|---|---|---|---|---|")
    ch = {n: b for (f, n), b in chain.items() if f == "BM_ChainForward"}
    for n in sorted(ch):
        b = ch[n]
        b["cpu_seconds"] = b["cpu_time"] * UNIT[b["time_unit"]]
        print(f"| {n} | {b['seconds'] * 1e6:.1f} µs | {b['cpu_seconds'] * 1e6:.1f} µs "
              f"| {'yes' if b['M_diagonal'] else 'no'} | {fmt_s(b['build_s'])} |")

    print("\n## Targets\n")
    print("| target | wall | CPU | |")
    print("|---|---|---|---|")
    if 8 in dc and 8 in sympy_derive:
        rw = sympy_derive[8]["seconds"] / dc[8]["seconds"]
        rc = sympy_derive[8]["cpu_seconds"] / dc[8]["build_cpu_s"]
        print(f"| derive + compile ≥ 50× faster than SymPy derive at N = 8 | {fmt_ratio(rw)} "
              f"| {fmt_ratio(rc)} | {verdict(rw >= 50, rc >= 50)} |")
    if 50 in dc:
        w, c = dc[50]["seconds"], dc[50]["build_cpu_s"]
        print(f"| derive + compile at N = 50 < 3 s | {fmt_s(w)} | {fmt_s(c)} | {verdict(w < 3, c < 3)} |")
    if 10 in fw:
        w = fw[10]["seconds"] * 1e6
        c = fw[10]["cpu_time"] * UNIT[fw[10]["time_unit"]] * 1e6
        print(f"| forward call at N = 10 < 2 µs | {w:.2f} µs | {c:.2f} µs | {verdict(w < 2, c < 2)} |")
    if 200 in ch and 50 in ch:
        rw = ch[200]["seconds"] / ch[50]["seconds"]
        rc = ch[200]["cpu_seconds"] / ch[50]["cpu_seconds"]
        print(f"| Cartesian chain t(200)/t(50) ≤ 5 | {rw:.1f} | {rc:.1f} | {verdict(rw <= 5, rc <= 5)} |")
    print("\nRatios compare measurements of this one run; absolute times vary by up to ±40 % "
          "between runs on this machine kind (docs/benchmarks.md, Peers).")


if __name__ == "__main__":
    main()
