"""cvode:jacobian and auto from Python (issue 22): Model.simulate, the Stepper and lagrange.sweep
integrate on the exact Jacobian as `lagrange simulate` does (docs/theory.md §5.6, "One Jacobian
for every entry point")."""

import csv
import subprocess

import numpy as np
import pytest

import lagrange
from conftest import SOURCE_DIR

TETHER = str(SOURCE_DIR / "examples" / "elastic_tether.yaml")


def cli_run(cli, tmp_path, integrator, t_end):
    out = tmp_path / f"{integrator.replace(':', '_')}.csv"
    subprocess.run([cli, "simulate", TETHER, "--integrator", integrator, "--t-end", repr(t_end),
                    "--compile", "off", "-o", str(out), "-q"], check=True, capture_output=True)
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in row] for row in rows[1:]])


def test_run_with_cvode_jacobian_is_the_cli_run(cli, tmp_path):
    header, table = cli_run(cli, tmp_path, "cvode:jacobian", 1.0)
    run = lagrange.load(TETHER).simulate(t_end=1.0, integrator="cvode:jacobian", compile="off")
    assert run.status == "complete"
    assert run.stats["method"] == "cvode:jacobian"
    assert run.columns == header
    assert (run.array == table).all()  # bit for bit: the same engine path


def test_auto_switches_in_a_run_and_in_a_sweep_as_in_the_cli(cli, tmp_path):
    header, table = cli_run(cli, tmp_path, "auto", 1.0)
    model = lagrange.load(TETHER)
    run = model.simulate(t_end=1.0, integrator="auto", compile="off")
    assert run.stats["method"].startswith("dop853, stiff at t = ")
    assert ": cvode:jacobian from t = " in run.stats["method"]
    assert (run.array == table).all()
    frame = lagrange.sweep(model, {"D": [3000.0]}, {"x_end": "final(x)", "z_low": "min(z)"},
                           t_end=1.0, integrator="auto")
    assert list(frame["status"]) == ["ok"]
    assert frame["x_end"][0] == run["x"][-1]
    # min() is located between samples (docs/theory.md §9.2): at or below the lowest sample.
    assert frame["z_low"][0] <= run["z"].min()
    assert frame["z_low"][0] == pytest.approx(run["z"].min(), abs=1e-3)


def test_stepper_with_cvode_jacobian_follows_one_run():
    model = lagrange.load(TETHER)
    run = model.simulate(t_end=1.0, output_step=0.05, integrator="cvode:jacobian", rtol=1e-8,
                         atol=1e-10)
    stepper = model.stepper(t_end=1.0, integrator="cvode:jacobian", rtol=1e-8, atol=1e-10)
    for _ in range(20):
        stepper.step(0.05)
    stepped = stepper.trajectory()
    assert stepped.stats["method"] == "cvode:jacobian"
    for name in ("x", "z", "line.node3.x", "line.node3.z"):
        assert np.abs(stepped[name] - run[name]).max() < 1e-6


def test_cvode_jacobian_on_the_recursive_form_says_what_to_do():
    model = lagrange.load(str(SOURCE_DIR / "examples" / "planar_arm_pd.yaml"))
    with pytest.raises(ValueError, match='dynamics="lagrangian"'):
        model.simulate(t_end=0.1, integrator="cvode:jacobian")
    # auto has no Jacobian there and runs DOP853 throughout
    assert model.simulate(t_end=0.1, integrator="auto").stats["method"] == "dop853"
