"""Runs in threads release the GIL and give the same numbers; models pickle for process pools."""

import pickle
import threading
import time
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import numpy as np
import pytest

import lagrange


@pytest.fixture(scope="module")
def pendulum(examples_dir):
    return lagrange.load(str(examples_dir / "double_pendulum.yaml"), set={"m2": 0.7},
                         initial={"theta2": 0.4})


def test_two_simulations_in_threads_equal_sequential_ones(examples_dir, pendulum):
    other = lagrange.load(str(examples_dir / "elastic_pendulum.yaml"))
    jobs = [(pendulum, 3.0), (other, 3.0), (pendulum, 2.0)]
    alone = [m.simulate(t_end=t).array.copy() for m, t in jobs]
    with ThreadPoolExecutor(max_workers=3) as pool:
        together = list(pool.map(lambda job: job[0].simulate(t_end=job[1]).array, jobs))
    for a, b in zip(alone, together):
        assert np.array_equal(a, b)


def test_simulate_releases_the_gil(examples_dir):
    # While a run integrates on another thread, this thread keeps running Python: it iterates
    # throughout the middle half of the run. Were the GIL held, it could not iterate at all
    # between the run's start and its end. (The longest pause is not a sound measure on a loaded
    # machine: the scheduler alone may park this thread for a large part of a short run.)
    tether = lagrange.load(str(examples_dir / "tether_in_wind.yaml"))
    worker = threading.Thread(target=tether.simulate, kwargs=dict(compile="off"))
    ticks = [time.perf_counter()]
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    duration = ticks[-1] - ticks[0]
    assert duration > 0.05, "the run is too short to show anything"
    assert len(ticks) > 100
    middle = [t for t in ticks if ticks[0] + duration / 4 < t < ticks[0] + 3 * duration / 4]
    assert len(middle) > 10


def test_forward_batch_releases_the_gil(pendulum):
    rng = np.random.default_rng(0)
    Q, V = rng.normal(size=(200000, 2)), rng.normal(size=(200000, 2))
    with ThreadPoolExecutor(max_workers=2) as pool:
        halves = list(pool.map(lambda s: pendulum.forward_batch(Q[s], V[s]),
                               [slice(0, 100000), slice(100000, None)]))
    assert np.array_equal(np.vstack(halves), pendulum.forward_batch(Q, V))


def test_pickle_round_trip_keeps_text_path_and_settings(pendulum):
    copy = pickle.loads(pickle.dumps(pendulum))
    assert copy.path == pendulum.path
    assert copy.parameters == pendulum.parameters and copy.parameters["m2"] == 0.7
    assert copy.initial_state[0][1] == 0.4
    assert np.array_equal(copy.simulate(t_end=1.0).array, pendulum.simulate(t_end=1.0).array)


def test_loads_model_pickles_without_a_file():
    text = "name: spring\nparameters: {k: 2}\ncoordinates:\n  x: {initial: 1}\n" \
           "kinetic: der(x)^2/2\npotential: k*x^2/2\n"
    m = lagrange.loads(text, set={"k": 4.0})
    copy = pickle.loads(pickle.dumps(m))
    assert copy.parameters == {"k": 4.0}
    assert np.array_equal(copy.forward([1.0], [0.0]), [-4.0])


def final_theta(model):
    return model.simulate(t_end=1.0)["theta1"][-1]


def test_a_process_pool_runs_pickled_models(pendulum):
    with ProcessPoolExecutor(max_workers=1) as pool:
        remote = pool.submit(final_theta, pendulum).result(timeout=60)
    assert remote == final_theta(pendulum)


def test_stepper_releases_the_gil(examples_dir):
    # As for simulate: one long step on another thread leaves this thread running Python.
    tether = lagrange.load(str(examples_dir / "tether_in_wind.yaml"))
    s = tether.stepper(compile="off")
    # Long enough (about a second; 60 s of it took 0.05 s) that a busy machine descheduling
    # this thread for a while (ctest runs other tests beside it) still leaves ticks in the
    # middle half.
    worker = threading.Thread(target=s.step, args=(1800.0,))
    ticks = [time.perf_counter()]
    worker.start()
    while worker.is_alive():
        ticks.append(time.perf_counter())
    worker.join()
    duration = ticks[-1] - ticks[0]
    assert duration > 0.05, "the step is too short to show anything"
    assert len(ticks) > 100
    middle = [t for t in ticks if ticks[0] + duration / 4 < t < ticks[0] + 3 * duration / 4]
    assert len(middle) > 10
