"""The Model's names and values, its equations, runs as numpy views, forward dynamics."""

import json

import numpy as np
import pytest

import lagrange


@pytest.fixture(scope="module")
def double_pendulum(examples_dir):
    return lagrange.load(str(examples_dir / "double_pendulum.yaml"), set={"l1": 1.2})


@pytest.fixture(scope="module")
def constrained(examples_dir):
    return lagrange.load(str(examples_dir / "constrained_pendulum.yaml"))


def test_names_and_values(double_pendulum):
    m = double_pendulum
    assert m.name == "double pendulum"
    assert m.coordinates == ["theta1", "theta2"]
    assert m.velocities == ["theta1_dot", "theta2_dot"]
    assert m.parameters["l1"] == 1.2  # the set= value replaces the file's
    assert m.columns[:5] == ["t", "theta1", "theta2", "theta1_dot", "theta2_dot"]
    assert m.inputs == []
    q, v = m.initial_state
    assert q.shape == (2,) and v.shape == (2,)


def test_derive_gives_the_cli_formats(double_pendulum):
    eq = double_pendulum.derive()
    assert "Mass matrix M(q)" in eq.text
    assert "\\begin{align*}" in eq._repr_latex_()
    assert "% " not in eq._repr_latex_() and "% Energies" in eq.latex  # headings become text
    assert "theta" in eq.latex and "\\" in eq.latex
    assert json.loads(eq.json)["name"] == "double pendulum"


def test_run_columns_are_views_of_one_buffer(double_pendulum):
    run = double_pendulum.simulate(t_end=1.0, output_step=0.1)
    assert len(run) == 11 and run.array.shape == (11, len(run.columns))
    assert np.array_equal(run.t, np.linspace(0, 1, 11))
    theta1 = run["theta1"]
    assert np.shares_memory(theta1, run.array) and np.shares_memory(run.t, run.array)
    assert np.array_equal(theta1, run.array[:, run.columns.index("theta1")])
    with pytest.raises(ValueError):
        theta1[0] = 1.0  # read-only: the engine's trajectory
    with pytest.raises(KeyError):
        run["nope"]
    del run  # the view keeps the trajectory alive
    assert theta1[0] == double_pendulum.initial_state[0][0]


def test_set_changes_the_run(examples_dir, double_pendulum):
    plain = lagrange.load(str(examples_dir / "double_pendulum.yaml"))
    a = plain.simulate(t_end=0.5)["theta1"]
    b = double_pendulum.simulate(t_end=0.5)["theta1"]
    assert a[0] == b[0] and a[-1] != b[-1]


def test_simulate_settings(double_pendulum):
    run = double_pendulum.simulate(t_end=0.2, output_step=0.05, integrator="rk4")
    assert run.stats["method"] == "rk4"
    with pytest.raises(ValueError, match="t-end must be positive"):
        double_pendulum.simulate(t_end=-1)


def test_to_pandas(double_pendulum):
    pd = pytest.importorskip("pandas")
    run = double_pendulum.simulate(t_end=0.2)
    df = run.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert list(df.columns) == run.columns
    assert np.array_equal(df["theta2"].to_numpy(), run["theta2"])


def test_forward_matches_the_run(double_pendulum):
    # The run's first accelerations are the model's at the initial state: the energy balance
    # is not needed, the pendulum starts at rest so v̇ from forward must move q as the run does.
    q, v = double_pendulum.initial_state
    a = double_pendulum.forward(q, v)
    assert a.shape == (2,)
    run = double_pendulum.simulate(t_end=0.01, output_step=0.001)
    dt = run.t[1]
    # q(dt) ≈ q0 + v0 dt + a dt²/2 to O(dt³)
    for i, name in enumerate(double_pendulum.coordinates):
        expected = q[i] + v[i] * dt + a[i] * dt * dt / 2
        assert run[name][1] == pytest.approx(expected, abs=1e-7)


def test_forward_batch_equals_a_loop_of_forward(double_pendulum):
    rng = np.random.default_rng(1)
    Q = rng.uniform(-3, 3, (50, 2))
    V = rng.uniform(-2, 2, (50, 2))
    A = double_pendulum.forward_batch(Q, V, t=0.5)
    assert A.shape == (50, 2)
    loop = np.array([double_pendulum.forward(q, v, t=0.5) for q, v in zip(Q, V)])
    assert np.array_equal(A, loop)


def test_forward_batch_constrained_gives_multipliers(constrained):
    q0, v0 = constrained.initial_state
    Q = np.tile(q0, (4, 1))
    V = np.tile(v0, (4, 1)) * np.arange(4)[:, None]
    A, L = constrained.forward_batch(Q, V)
    assert A.shape == (4, len(constrained.velocities))
    assert L.shape == (4, len(constrained.constraints))
    for r in range(4):
        a, lam = constrained.forward(Q[r], V[r])
        assert np.array_equal(a, A[r]) and np.array_equal(lam, L[r])


def test_shapes_are_checked(double_pendulum):
    with pytest.raises(ValueError, match=r"q: expected 2 values, got an array of shape \(3,\)"):
        double_pendulum.forward([0, 0, 0], [0, 0])
    with pytest.raises(ValueError, match=r"Q: expected an array of shape \(rows, 2\)"):
        double_pendulum.forward_batch(np.zeros((3, 3)), np.zeros((3, 2)))
    with pytest.raises(ValueError, match="expected 3 rows like Q"):
        double_pendulum.forward_batch(np.zeros((3, 2)), np.zeros((2, 2)))


def test_export_c_writes_the_sources(double_pendulum, tmp_path):
    double_pendulum.export_c(str(tmp_path))
    header = (tmp_path / "lagrange_model.h").read_text()
    assert "theta1" in header or "LAGRANGE" in header
    assert (tmp_path / "lagrange_model.c").stat().st_size > 1000


def test_report_is_the_commands_html(double_pendulum, tmp_path):
    run = double_pendulum.simulate(t_end=1.0)
    path = tmp_path / "dp.html"
    run.report(str(path))
    html = path.read_text()
    assert html.lower().startswith("<!doctype html>") and "double pendulum" in html
    inline = run._repr_html_()
    assert inline.startswith("<iframe") and "&quot;" in inline and '"en"' not in inline
    with pytest.raises(ValueError, match="expected a file name ending in .html"):
        run.report(str(tmp_path / "dp.txt"))


def test_initial_replaces_the_files_state(examples_dir):
    m = lagrange.load(str(examples_dir / "double_pendulum.yaml"),
                      initial={"theta1": 0.3, "theta2_dot": -1.5})
    q, v = m.initial_state
    assert q[0] == 0.3 and v[1] == -1.5
    run = m.simulate(t_end=0.1)
    assert run["theta1"][0] == 0.3 and run["theta2_dot"][0] == -1.5
    with pytest.raises(ValueError, match="initial: no coordinate or velocity 'nope'"):
        lagrange.load(str(examples_dir / "double_pendulum.yaml"), initial={"nope": 1.0})
