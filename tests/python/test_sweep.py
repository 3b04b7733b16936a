"""lagrange.sweep (issue 24): each case's metrics equal, bit for bit, those of the lone run
`lagrange simulate --set` makes, run here, through a process pool and through a real Dask
scheduler with two worker processes on the loopback interface; bad input raises before any case
runs."""

import csv
import subprocess
from concurrent.futures import ProcessPoolExecutor
import multiprocessing

import numpy as np
import pytest

import lagrange
from conftest import SOURCE_DIR

MODEL = str(SOURCE_DIR / "examples" / "double_pendulum.yaml")
GRID = {"l2": [0.5, 1.0, 1.5], "m2": [1.0, 2.5]}
METRICS = {"last": "final(theta1)", "peak": "max(abs(theta2), t > 1)"}
T_END = 2.0


def lone_metrics(cli, tmp_path, l2, m2):
    """The metrics computed from `simulate --set`'s CSV of one case."""
    out = tmp_path / f"alone_{l2}_{m2}.csv"
    subprocess.run([cli, "simulate", MODEL, "--set", f"l2={l2!r}", "--set", f"m2={m2!r}",
                    "--t-end", repr(T_END), "-o", str(out), "-q"], check=True,
                   capture_output=True)
    with open(out, newline="") as f:
        rows = list(csv.reader(f))
    table = np.array([[float(x) for x in row] for row in rows[1:]])
    t, theta1, theta2 = table[:, 0], table[:, rows[0].index("theta1")], table[:, rows[0].index("theta2")]
    return theta1[-1], np.max(np.abs(theta2[t > 1]))


@pytest.fixture(scope="module")
def expected(cli, tmp_path_factory):
    tmp = tmp_path_factory.mktemp("alone")
    return {(l2, m2): lone_metrics(cli, tmp, l2, m2) for l2 in GRID["l2"] for m2 in GRID["m2"]}


def check(frame, expected):
    assert len(frame) == 6
    assert list(frame["status"]) == ["ok"] * 6
    for _, row in frame.iterrows():
        last, peak = expected[(row["l2"], row["m2"])]
        assert row["last"] == last  # bit for bit
        # located between samples (docs/theory.md §9.2): at least the largest sample, near it
        assert peak <= row["peak"] <= peak * (1 + 1e-2)


def test_sweep_here_equals_lone_runs(expected, cli, tmp_path):
    model = lagrange.load(MODEL)
    frame = lagrange.sweep(model, GRID, METRICS, t_end=T_END)
    assert list(frame.columns[:2]) == ["l2", "m2"]
    assert list(frame["l2"]) == [0.5, 0.5, 1.0, 1.0, 1.5, 1.5]  # last name fastest
    check(frame, expected)
    # The cases' inputs from one traced read and its check, as `lagrange sweep` has them, whose
    # summary holds the same bits; the model keeps that read for the next study.
    assert frame.attrs["model_reads"] == 2
    study = tmp_path / "study"
    subprocess.run([cli, "sweep", MODEL, "--vary", "l2=0.5,1.0,1.5", "--vary", "m2=1.0,2.5",
                    "--t-end", repr(T_END), "-o", str(study), "-q"]
                   + [f"--metric={name}={expr}" for name, expr in METRICS.items()],
                   check=True, capture_output=True)
    with open(study / "summary.csv", newline="") as f:
        summary = list(csv.DictReader(f))
    for name in METRICS:
        assert [float(row[name]) for row in summary] == list(frame[name])
    again = lagrange.sweep(model, {"l2": [0.75], "m2": [1.5]}, METRICS, t_end=T_END)
    assert again.attrs["model_reads"] == 0
    assert list(again["last"]) == [lone_metrics(cli, tmp_path, 0.75, 1.5)[0]]


def test_sweep_through_a_process_pool(expected):
    model = lagrange.load(MODEL)
    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        frame = lagrange.sweep(model, GRID, METRICS, executor=pool, chunk=2, t_end=T_END)
    check(frame, expected)


@pytest.fixture(scope="module")
def dask_client():
    """A Dask scheduler and two worker processes on the loopback interface, for this module."""
    distributed = pytest.importorskip("distributed", reason="python3-distributed is not installed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  host="127.0.0.1", dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        yield client


def test_sweep_through_a_dask_cluster(expected, dask_client):
    assert len(dask_client.scheduler_info()["workers"]) == 2
    model = lagrange.load(MODEL)
    frame = lagrange.sweep(model, GRID, METRICS, executor=dask_client.get_executor(), chunk=1,
                           t_end=T_END)
    check(frame, expected)


def test_a_dask_worker_killed_mid_sweep_loses_nothing(dask_client):  # last: it kills a worker
    """SIGKILL of one of two Dask workers part-way: the scheduler runs its chunks again on the
    other (and on the restarted one), and every case arrives once, as a run here gives it."""
    import os
    import signal
    import threading
    import time

    model = lagrange.load(MODEL)
    cases = [{"l2": 0.5 + 0.02 * i} for i in range(60)]
    here = lagrange.sweep(model, cases, ["final(theta1)"], t_end=60.0)
    victim = sorted(dask_client.run(os.getpid).values())[0]
    result = {}
    runner = threading.Thread(target=lambda: result.update(frame=lagrange.sweep(
        model, cases, ["final(theta1)"], executor=dask_client.get_executor(), chunk=1,
        t_end=60.0)))
    runner.start()
    time.sleep(0.3)
    killed = runner.is_alive()
    os.kill(victim, signal.SIGKILL)
    runner.join(120)
    assert not runner.is_alive()
    frame = result["frame"]
    assert len(frame) == len(cases)
    assert list(frame["final(theta1)"]) == list(here["final(theta1)"])
    if not killed:
        pytest.skip("the sweep finished before the worker was killed")


def test_failing_cases_are_rows_with_their_reason():
    model = lagrange.load(MODEL)
    frame = lagrange.sweep(model, [{"m2": 1.0}, {"m2": 0.0}], ["final(theta2)"], t_end=1.0)
    assert list(frame["status"]) == ["ok", "failed"]
    assert frame["reason"][1]
    assert np.isfinite(frame["final(theta2)"][0])


@pytest.mark.parametrize("grid, metrics, fragment", [
    ({"k": [1.0]}, ["final(theta1)"], "no parameter 'k'"),
    ({"l2": [1.0]}, ["max(theta3)"], "unknown name 'theta3'"),
    ({"l2": [1.0]}, ["median(theta1)"], "unknown aggregate"),
    ({"l2": []}, ["final(theta1)"], "at least one parameter"),
])
def test_bad_input_raises_before_any_case_runs(grid, metrics, fragment):
    model = lagrange.load(MODEL)
    with pytest.raises(ValueError, match=fragment.replace("(", r"\(")):
        lagrange.sweep(model, grid, metrics)


# issue 37 items 6, 7 and 14: each of these once returned a frame (empty, with failed rows, with
# a case per character of "12", with a metric column overwriting a parameter's) or blamed another
# parameter; now each raises ValueError naming the mistake before any case runs.
@pytest.mark.parametrize("grid, metrics, options, fragment", [
    (GRID, METRICS, {"chunk": -1, "executor": object()}, "chunk must be a whole number"),
    (GRID, METRICS, {"chunk": 0, "executor": object()}, "chunk must be a whole number"),
    (GRID, METRICS, {"t_end": -1}, "--t-end must be positive"),
    ({"m2": "12"}, METRICS, {}, "expected a sequence of numbers for 'm2', got '12'"),
    ({"m2": [1.0, float("nan")]}, METRICS, {}, "expected a finite number for 'm2'"),
    ([{"m2": float("inf")}], METRICS, {}, "expected a finite number for 'm2'"),
    (GRID, {"m2": "final(theta1)"}, {}, "metric 'm2' is named like a parameter"),
    (GRID, {"status": "final(theta1)"}, {}, "metric 'status' is named like a column"),
    (GRID, ["case=final(theta1)"], {}, "metric 'case' is named like a column"),
])
def test_hostile_study_arguments_raise(grid, metrics, options, fragment):
    model = lagrange.load(MODEL)
    with pytest.raises(ValueError, match=fragment.replace("(", r"\(").replace(")", r"\)")):
        lagrange.sweep(model, grid, metrics, **options)


def test_loads_refuses_an_unknown_dynamics_and_non_finite_values():
    text = (SOURCE_DIR / "examples" / "pendulum.yaml").read_text()
    with pytest.raises(ValueError, match="dynamics: expected auto, lagrangian or recursive, got 'bogus'"):
        lagrange.loads(text, dynamics="bogus")
    with pytest.raises(ValueError, match=r"set m=nan: expected a finite number"):
        lagrange.loads(text, set={"m": float("nan")})


def test_loads_refuses_a_label_that_could_spoof_a_location_and_oversized_text():
    text = (SOURCE_DIR / "examples" / "pendulum.yaml").read_text()
    with pytest.raises(ValueError, match="label: expected one line of printable text"):
        lagrange.loads(text, label="model.yaml:1:1: error: fake\nreal.yaml")
    with pytest.raises(lagrange.ModelError, match="expected a model of at most 16 MiB"):
        lagrange.loads(text + "#" * (16 << 20))


ROTOR = str(SOURCE_DIR / "tests" / "cli" / "data" / "wind_rotor.yaml")


def test_an_optimisation_study_is_the_commands(cli, tmp_path):
    """sweep(optimize=True) gives `lagrange sweep --optimize`'s rows on the rotor's power curve
    (tests/cli/data/wind_rotor.yaml): the same starts, objectives and iterations, the
    infeasible case below the cut-in wind failed and the others solved."""
    import pandas

    study = tmp_path / "curve"
    winds = [0.5, 4.0, 8.0, 12.0, 16.0]
    subprocess.run([cli, "sweep", ROTOR, "--optimize", "--vary", "W=" + ",".join(map(repr, winds)),
                    "--metric", "u_max=max(u)", "-o", str(study), "-q"], check=True,
                   capture_output=True)
    with open(study / "summary.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    frame = lagrange.sweep(lagrange.load(ROTOR), {"W": winds}, {"u_max": "max(u)"}, optimize=True)
    assert list(frame["status"]) == ["failed", "ok", "ok", "ok", "ok"]
    for (_, got), row in zip(frame.iterrows(), rows):
        assert got["status"] == row["status"]
        assert got["iterations"] == int(row["iterations"])
        assert pandas.isna(got["warm_start"]) == (row["warm_start"] == "")
        if row["status"] == "ok":
            assert got["objective"] == float(row["objective"])
            assert got["u_max"] == float(row["u_max"])
    # Monotone in the wind, every case after the file's W = 8 started from its neighbour.
    ok = frame[frame["status"] == "ok"]
    assert np.all(np.diff(ok["objective"].to_numpy()) > 0)
    # (W = 0.5 started from W = 4, failed, and was solved again from the problem's guess.)
    starts = [None if pandas.isna(x) else int(x) for x in frame["warm_start"]]
    assert starts == [None, 2, None, 2, 3]
    with pytest.raises(ValueError, match="do not apply"):
        lagrange.sweep(lagrange.load(ROTOR), {"W": winds}, {}, optimize=True, t_end=3)
