"""Model.optimize solves the file's optimal_control problem as `lagrange optimize` does: the same
objective and the same collocated trajectory, bit for bit, and errors that say what is wrong."""

import csv
import subprocess

import numpy as np
import pytest

import lagrange
from conftest import SOURCE_DIR

OPTIMAL = SOURCE_DIR / "examples" / "optimal"


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in row] for row in rows[1:]])


@pytest.mark.parametrize("name", ["cart_pole_swing_up.yaml", "pendulum_swing_up_cartesian.yaml"])
def test_optimize_matches_the_cli(name, cli, tmp_path):
    path = OPTIMAL / name
    out = tmp_path / "opt.csv"
    done = subprocess.run([cli, "optimize", str(path), "-o", str(out), "--intervals", "20"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    r = lagrange.load(str(path)).optimize(intervals=20)
    assert r.optimal, r.status
    assert f"objective          {r.objective:.10g}" in done.stdout
    header, table = read_csv(out)
    assert header == r.run.columns
    got = np.column_stack([r.run[c] for c in header])
    np.testing.assert_array_equal(got, table)
    assert r.controls.shape == (20, len(r.control_names))
    # The controls are the run's control column, one value per interval.
    column = np.asarray(r.run[r.control_names[0]])
    assert column[1] == r.controls[0, 0]


def test_the_double_integrators_minimum_energy_is_the_closed_form():
    # u constant on N intervals: J = 12 / (1 - 1/N^2) (docs/theory.md §10).
    r = lagrange.load(str(OPTIMAL / "double_integrator_min_energy.yaml")).optimize(intervals=10)
    assert r.optimal
    assert r.objective == pytest.approx(12 / (1 - 1 / 100), rel=1e-9)
    assert r.active_bounds == []  # u is unbounded, the end states fixed


def test_the_energy_balance_names_each_sources_work(cli):
    # From rest at x = 0 to speed 1 at x = 1: H gains m/2 + k/2 = 2, the force's work less the
    # damper's (docs/theory.md §10, "Checks"); the CLI prints the same figures.
    data = SOURCE_DIR / "tests" / "optimize" / "data" / "spring_damper_to_speed.yaml"
    e = lagrange.load(str(data)).optimize().energy_balance
    assert e.unsuitable == ""
    assert e.change == pytest.approx(2.0, abs=1e-9)
    damper = "damper 'anchor'–'mass' (line 19)"
    assert list(e.work) == ["force at 'mass' (line 21)", damper]
    assert sum(e.work.values()) == pytest.approx(2.0, abs=1e-8)
    assert e.work[damper] < -0.1
    assert e.relative_residual < 1e-8
    done = subprocess.run([cli, "optimize", str(data)], capture_output=True, text=True, check=True)
    assert "energy balance     H(T) - H(0) = 2, the work over [0, T]:" in done.stdout
    assert f"{e.work[damper]:+.6g}  {damper}" in done.stdout


def test_homotopy_stages_are_reported_with_the_problems_result():
    # A fictitious force at price w = 10 in the stage: w/(1 + w) of the problem's 12/(1 - 1/N^2)
    # (docs/theory.md §10, "Homotopy"); the problem itself then reaches 12/(1 - 1/N^2).
    data = SOURCE_DIR / "tests" / "optimize" / "data" / "double_integrator_fictitious.yaml"
    r = lagrange.load(str(data)).optimize()
    assert r.optimal, r.status
    assert [s.name for s in r.stages] == ["fictitious"]
    stage = r.stages[0]
    assert stage.optimal and stage.iterations > 0
    assert stage.objective == pytest.approx(10 / 11 * 12 / (1 - 1 / 100), rel=1e-8)
    assert stage.tracking == 0
    assert r.objective == pytest.approx(12 / (1 - 1 / 100), rel=1e-9)


def test_a_free_bodys_slew_is_the_double_integrators_closed_form():
    # A quarter turn of an isotropic body (J = 2) at rest to rest in T = 2 s: the fixed-axis turn
    # on the double-integrator schedule, J_N = 12 J² θ² / (T³ (1 − 1/N²)) (docs/theory.md §10).
    r = lagrange.load(str(OPTIMAL / "attitude_slew.yaml")).optimize(intervals=20)
    assert r.optimal, r.status
    theta = np.pi / 2
    assert r.objective == pytest.approx(12 * 4 * theta**2 / (8 * (1 - 1 / 400)), rel=1e-6)
    assert np.asarray(r.run["sat.R21"])[-1] == pytest.approx(1.0, abs=2e-6)
    assert np.abs(r.controls[:, :2]).max() < 1e-6  # about z only


def test_a_polynomial_control_has_a_value_at_each_collocation_point():
    # u = 6 - 12t is linear: polynomial controls hold it exactly, J = 12 at N = 2 (docs/theory.md
    # §10, "Polynomial controls"); the run's control column carries the points' values.
    path = SOURCE_DIR / "tests" / "optimize" / "data" / "double_integrator_polynomial.yaml"
    r = lagrange.load(str(path)).optimize(verify=True)
    assert r.optimal, r.status
    assert r.objective == pytest.approx(12, abs=1e-8)
    assert r.polynomial == [True]
    assert r.control_points.shape == (2, 3, 1)
    np.testing.assert_array_equal(np.asarray(r.run["u"])[1:], r.control_points.ravel())
    t = np.asarray(r.run["t"])
    np.testing.assert_allclose(np.asarray(r.run["u"]), 6 - 12 * t, atol=1e-7)
    np.testing.assert_allclose(r.controls[:, 0], [3, -3], atol=1e-7)  # the interval means
    assert r.verify.final_gap < 1e-8


def test_verify_re_simulates_onto_the_collocated_end():
    r = lagrange.load(str(OPTIMAL / "pendulum_swing_up_polar.yaml")).optimize(verify=True)
    assert r.verify.message == ""
    assert r.verify.final_gap < 1e-2
    assert lagrange.load(str(OPTIMAL / "cart_pole_swing_up.yaml")).optimize(
        intervals=10).verify is None


def test_a_failure_is_a_result_not_an_exception():
    r = lagrange.load(str(OPTIMAL / "cart_pole_swing_up.yaml")).optimize(
        intervals=10, ipopt={"max_iter": 2})
    assert not r.optimal
    assert "maximum number of iterations" in r.status


def test_the_hessian_choice_reaches_the_same_optimum():
    m = lagrange.load(str(OPTIMAL / "cart_pole_swing_up.yaml"))
    exact, lbfgs = m.optimize(intervals=20), m.optimize(intervals=20, hessian="limited-memory")
    assert exact.exact_hessian and not lbfgs.exact_hessian
    assert exact.hessian_note == ""
    assert lbfgs.objective == pytest.approx(exact.objective, rel=1e-6)


def test_the_compile_choice_changes_no_iterate_and_says_which_ran():
    m = lagrange.load(str(OPTIMAL / "cart_pole_swing_up.yaml"))
    on, off = m.optimize(intervals=20, compile="on"), m.optimize(intervals=20, compile="off")
    assert on.hessian_evaluation.startswith("machine code")
    assert off.hessian_evaluation == "interpreter"
    assert on.residual_evaluation.startswith("machine code")
    assert off.residual_evaluation == "interpreter"
    assert on.iterations == off.iterations
    assert on.objective == off.objective  # the same bits: the library computes the interpreter's


def test_bad_requests_say_what_is_wrong(examples_dir):
    with pytest.raises(ValueError, match="no optimal_control section"):
        lagrange.load(str(examples_dir / "pendulum.yaml")).optimize()
    with pytest.raises(ValueError, match="degree from 1 to 5"):
        lagrange.load(str(OPTIMAL / "cart_pole_swing_up.yaml")).optimize(degree=7)
    with pytest.raises(ValueError, match="expected hessian"):
        lagrange.load(str(OPTIMAL / "cart_pole_swing_up.yaml")).optimize(hessian="newton")
    with pytest.raises(ValueError, match="compile: expected auto, on or off"):
        lagrange.load(str(OPTIMAL / "cart_pole_swing_up.yaml")).optimize(compile="sometimes")
