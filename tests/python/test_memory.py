"""Reference counts do not leak: the resident set stays flat over 10^5 calls (issue 23)."""

import os

import numpy as np

import lagrange


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def grows_by(fn, calls, warm_up):
    for _ in range(warm_up):
        fn()
    before = resident_bytes()
    for _ in range(calls):
        fn()
    return resident_bytes() - before


def test_forward_does_not_leak(examples_dir):
    m = lagrange.load(str(examples_dir / "double_pendulum.yaml"))
    q, v = np.array([0.3, -0.2]), np.array([0.1, 0.0])
    # 10^5 calls each making a 2-vector (~100 bytes with its header): a leak would show 10 MB.
    assert grows_by(lambda: m.forward(q, v), 100000, 10000) < 2 << 20


def test_runs_and_their_views_are_freed(examples_dir):
    m = lagrange.load(str(examples_dir / "double_pendulum.yaml"))

    def run_and_view():
        run = m.simulate(t_end=1.0)  # 101 rows × 10 columns: 8 kB per run
        return run["theta1"][-1] + run.array[0, 0]

    # 2000 runs: 16 MB if the trajectories or their views were kept.
    assert grows_by(run_and_view, 2000, 200) < 4 << 20
