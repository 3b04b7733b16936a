#!/usr/bin/env python3
"""An FMU from `lagrange export --fmu` checked by FMPy, an importer no one here wrote (docs/fmu.md).

FMPy (github.com/CATIA-Systems/FMPy) is used from its source tree: give its path as FMPY_SRC (the
directory holding src/fmpy). Its logging helper is compiled here from native/src/logging/logging.c
against the FMI 2.0 headers vendored in src/io/fmi2; FMPy's CVode binaries are not built, so Model
Exchange runs with FMPy's explicit Euler solver. Needs Debian's python3-numpy and python3-lxml.

    FMPY_SRC=/path/to/FMPy python3 bench/fmu_fmpy.py build/lagrange examples/pendulum.yaml

For the model it: exports the FMU; validates it with fmpy.validation.validate_fmu (the XML against
FMI 2.0's schema and FMPy's consistency checks); simulates it in Co-Simulation with FMPy and
compares every column lagrange simulate also writes on the same grid; runs Model Exchange with
FMPy's explicit Euler at two step sizes (the difference from simulate should halve with the
step); prints the largest differences per column.
"""
import csv
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def build_logging(fmpy_src):
    target = os.path.join(fmpy_src, "src", "fmpy", "logging", "linux64", "logging.so")
    if not os.path.exists(target):
        subprocess.run(["cc", "-shared", "-fPIC", "-O1", "-I", os.path.join(ROOT, "src", "io", "fmi2"),
                        "-o", target, os.path.join(fmpy_src, "native", "src", "logging", "logging.c")],
                       check=True)


def main():
    if len(sys.argv) != 3 or "FMPY_SRC" not in os.environ:
        sys.exit(__doc__)
    lagrange, model = sys.argv[1], sys.argv[2]
    fmpy_src = os.environ["FMPY_SRC"]
    build_logging(fmpy_src)
    sys.path.insert(0, os.path.join(fmpy_src, "src"))
    import fmpy
    from fmpy.validation import validate_fmu

    work = tempfile.mkdtemp(prefix="lagrange-fmpy-")
    fmu = os.path.join(work, "model.fmu")
    subprocess.run([lagrange, "export", model, "--fmu", fmu], check=True)
    problems = validate_fmu(fmu)
    print(f"FMPy {fmpy.__version__} validate_fmu: {len(problems)} problems")
    for p in problems:
        print("  ", p)
    t_end, step = 2.0, 0.01
    ref_csv = os.path.join(work, "ref.csv")
    subprocess.run([lagrange, "simulate", model, "--t-end", str(t_end), "--output-step", str(step),
                    "-o", ref_csv, "-q"], check=True)
    with open(ref_csv) as f:
        ref = list(csv.DictReader(f))
    # FMPy's Euler takes one step per output interval: Model Exchange is recorded every h and
    # compared on simulate's grid, for two h, to show first-order convergence to simulate's run.
    runs = [("CoSimulation", step, {}), ("ModelExchange", 2e-4, {"solver": "Euler", "step_size": 2e-4}),
            ("ModelExchange", 1e-4, {"solver": "Euler", "step_size": 1e-4})]
    for fmi_type, interval, options in runs:
        res = fmpy.simulate_fmu(fmu, fmi_type=fmi_type, stop_time=t_end, output_interval=interval,
                                **options)
        names = [n for n in res.dtype.names if n != "time" and n in ref[0]]
        worst = {}
        for row in res:
            r = round(row["time"] / step)
            if r >= len(ref) or abs(float(ref[r]["t"]) - row["time"]) > 1e-9:
                continue
            for n in names:
                worst[n] = max(worst.get(n, 0.0), abs(float(ref[r][n]) - row[n]))
        print(f"{fmi_type} (output interval {interval:g}): {len(res)} rows; "
              "largest |FMPy - simulate| per column:")
        for n in names:
            print(f"  {n:20s} {worst.get(n, float('nan')):.3g}")


if __name__ == "__main__":
    main()
