"""examples/fmu (docs/fmu.md, "Examples"): the figure-eight kite exported as an FMU whose roll is
an FMI input, flown by examples/fmu/fly_figure_eight.py, a Python controller driving the FMU
through ctypes, against `lagrange simulate examples/figure_eight.yaml`, where the same law is
written in the model and evaluated continuously (the script samples it every 0.05 s and holds it).

Needs only the CLI and the standard library (not the module): the script is what a user runs.
"""

import csv
import subprocess
import sys

from conftest import SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples"
STEP = 0.05
T_END = 60.0  # six orbits: the first two settle, the last ones are the file's 9.77 s orbit


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    return {name: [float(row[name]) for row in rows] for name in rows[0]}


def crossings(t, x, upward):
    """Times where x crosses 0 (from below when upward, else from above), interpolated."""
    sign = 1 if upward else -1
    return [t[i - 1] + (t[i] - t[i - 1]) * x[i - 1] / (x[i - 1] - x[i])
            for i in range(1, len(x)) if sign * x[i - 1] < 0 <= sign * x[i]]


def test_python_controller_flies_the_fmu_in_figure_eights(cli, tmp_path):
    fmu = tmp_path / "figure_eight_roll_input.fmu"
    subprocess.run([str(cli), "export", str(EXAMPLES / "fmu" / "figure_eight_roll_input.yaml"),
                    "--fmu", str(fmu)], check=True, capture_output=True, timeout=120)
    flown = subprocess.run([sys.executable, str(EXAMPLES / "fmu" / "fly_figure_eight.py"), str(fmu),
                            "--t-end", str(T_END), "--step", str(STEP),
                            "--csv", str(tmp_path / "flight.csv")],
                           capture_output=True, text=True, timeout=120)
    assert flown.returncode == 0, flown.stderr
    assert flown.stderr == ""  # the FMU logged nothing: no error, no warning
    assert f"{round(T_END / STEP)} steps of {STEP:g} s" in flown.stdout
    fmu_run = read_csv(tmp_path / "flight.csv")

    subprocess.run([str(cli), "simulate", str(EXAMPLES / "figure_eight.yaml"),
                    "--t-end", str(T_END), "--output-step", str(STEP),
                    "-o", str(tmp_path / "law_in_model.csv")],
                   check=True, capture_output=True, timeout=120)
    reference = read_csv(tmp_path / "law_in_model.csv")
    t = fmu_run["t"]
    assert len(t) == len(reference["t"]) and t[-1] == reference["t"][-1] == T_END

    # The controller's roll is the input that acts: the FMU's wing.roll is the roll_cmd set ...
    assert fmu_run["wing.roll"] == fmu_run["roll_cmd"]
    assert max(fmu_run["roll_cmd"]) > 0.6 and min(fmu_run["roll_cmd"]) < -0.6  # both loops
    # ... and without it the file's default roll_cmd = 0 flies the kite into the ground.
    subprocess.run([str(cli), "simulate", str(EXAMPLES / "fmu" / "figure_eight_roll_input.yaml"),
                    "--t-end", "10", "--output-step", str(STEP),
                    "-o", str(tmp_path / "no_roll.csv")],
                   check=True, capture_output=True, timeout=120)
    assert min(read_csv(tmp_path / "no_roll.csv")["wing.elevation"]) < 0

    # Figure eights: the azimuth changes sign twice per orbit, up and down alternating, at the
    # times the continuous law crosses (the 0.05 s hold delays the orbit by a few hundredths).
    for upward in (True, False):
        mine = crossings(t, fmu_run["wing.azimuth"], upward)
        theirs = crossings(reference["t"], reference["wing.azimuth"], upward)
        assert len(mine) == len(theirs) >= 5, (mine, theirs)
        assert all(abs(a - b) < 0.1 for a, b in zip(mine, theirs)), (mine, theirs)
        # the settled orbit: the last period within 0.5 % of the continuous law's and within 1 %
        # of the 9.77 s examples/figure_eight.yaml states
        period, reference_period = mine[-1] - mine[-2], theirs[-1] - theirs[-2]
        assert abs(period / reference_period - 1) < 0.005, (period, reference_period)
        assert abs(period / 9.77 - 1) < 0.01, period
    azimuth = fmu_run["wing.azimuth"]
    up, down = crossings(t, azimuth, True), crossings(t, azimuth, False)
    assert all(d < u for d, u in zip(down, up)) and all(u < d for u, d in zip(up, down[1:]))

    # Airborne all along, over the same range of azimuth and elevation as the continuous law.
    assert min(fmu_run["wing.height"]) > 50
    for column in ("wing.azimuth", "wing.elevation"):
        assert abs(min(fmu_run[column]) - min(reference[column])) < 0.02, column
        assert abs(max(fmu_run[column]) - max(reference[column])) < 0.02, column
    # The kite's path over the first 5 s within 2 m (1 % of the 200 m tether) of the law's.
    for i in range(round(5 / STEP) + 1):
        gap = sum((fmu_run[k][i] - reference[k][i]) ** 2 for k in "xyz") ** 0.5
        assert gap < 2.0, (t[i], gap)
