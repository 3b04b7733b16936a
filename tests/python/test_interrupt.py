"""Ctrl-C during a run started from Python (issue 36 item 14, docs/python.md "Interrupting a
run"): simulate, sweep and optimize raise KeyboardInterrupt soon after SIGINT and keep what they
computed, as the command line does: the run so far (.run), the finished cases (.frame), the
last iterate (.result)."""

import json
import os
import signal
import subprocess
import sys
import time

import pytest

from conftest import SOURCE_DIR

EXAMPLES = SOURCE_DIR / "examples"

# Each child prints "ready", sleeps, then starts a run that would take minutes; the parent sends
# SIGINT once the run is under way. The child prints what the KeyboardInterrupt carried as JSON.
PRELUDE = """
import json, math, sys, time
import lagrange
{load}
print("ready", flush=True)
time.sleep(0.5)
start = time.monotonic()
try:
    {call}
    print(json.dumps({{"outcome": "returned"}}), flush=True)
except KeyboardInterrupt as e:
    seconds = time.monotonic() - start
{report}
"""


def interrupt(load, call, report, wait=2.5):
    """Runs the child, sends SIGINT `wait` s after it is ready; (its JSON, seconds to exit)."""
    code = PRELUDE.format(load=load, call=call, report=report)
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
    try:
        assert child.stdout.readline().strip() == "ready", child.stderr.read()
        time.sleep(wait)
        assert child.poll() is None, "the run ended before Ctrl-C: " + child.stderr.read()
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=60)
        took = time.monotonic() - sent
    finally:
        child.kill()
    assert child.returncode == 0, err
    return json.loads(out.strip().splitlines()[-1]), took


def test_ctrl_c_stops_simulate_and_keeps_the_rows():
    result, took = interrupt(
        f"m = lagrange.load({str(EXAMPLES / 'double_pendulum.yaml')!r})",
        "m.simulate(t_end=1e6, output_step=0.01, compile='off')",
        "    run = e.run\n"
        "    print(json.dumps({'outcome': 'interrupted', 'status': run.status, 'rows': len(run),"
        " 't_last': float(run.t[-1]), 'energy_spread': float(run['energy'].max() -"
        " run['energy'].min()), 'seconds': seconds}), flush=True)")
    assert result["outcome"] == "interrupted"
    assert took < 10
    assert result["status"] == "interrupted"
    # Rows were kept: more than a second of simulated time, far from t_end, and physically sound
    # (the double pendulum conserves energy).
    assert result["rows"] > 100
    assert 1.0 < result["t_last"] < 1e6
    assert result["energy_spread"] < 1e-3


def test_ctrl_c_stops_sweep_and_keeps_the_finished_cases():
    grid = "{'k': [20.0 + 0.01 * i for i in range(20000)]}"
    result, took = interrupt(
        # pandas imported before "ready": on a busy machine its import alone can take seconds.
        f"import pandas\nm = lagrange.load({str(EXAMPLES / 'elastic_pendulum.yaml')!r})",
        f"lagrange.sweep(m, {grid}, {{'peak': 'max(abs(theta))'}}, t_end=20, output_step=0.01)",
        "    f = e.frame\n"
        "    print(json.dumps({'outcome': 'interrupted', 'rows': len(f),"
        " 'cases': [int(i) for i in f.index], 'k': [float(k) for k in f['k']],"
        " 'status': sorted(set(f['status'])), 'peak': [float(p) for p in f['peak']],"
        " 'seconds': seconds}), flush=True)")
    assert result["outcome"] == "interrupted"
    assert took < 10
    # Some cases finished, not all; each row is its own case's.
    assert 0 < result["rows"] < 20000
    assert result["status"] == ["ok"]
    assert len(set(result["cases"])) == result["rows"]
    for case, k in zip(result["cases"], result["k"]):
        assert k == pytest.approx(20.0 + 0.01 * case)
    assert all(0 < p < 10 for p in result["peak"])


def test_ctrl_c_stops_optimize_at_the_last_iterate():
    path = EXAMPLES / "optimal" / "cart_pole_swing_up.yaml"
    result, took = interrupt(
        f"m = lagrange.load({str(path)!r}, dynamics='lagrangian')",
        # Tolerances no iterate meets: Ipopt would iterate for minutes.
        "m.optimize(intervals=400, ipopt={'tol': 1e-30, 'acceptable_tol': 1e-30,"
        " 'acceptable_obj_change_tol': 0.0, 'acceptable_constr_viol_tol': 1e-30,"
        " 'acceptable_dual_inf_tol': 1e-30, 'acceptable_compl_inf_tol': 1e-30,"
        " 'max_iter': 100000})",
        "    r = e.result\n"
        "    print(json.dumps({'outcome': 'interrupted', 'optimal': r.optimal, 'status': r.status,"
        " 'iterations': r.iterations, 'run_status': r.run.status, 'rows': len(r.run),"
        " 'seconds': seconds}), flush=True)",
        wait=4.0)
    assert result["outcome"] == "interrupted"
    assert took < 15
    assert not result["optimal"]
    assert result["status"].startswith("interrupted after")
    assert result["run_status"] == "interrupted"
    # Ctrl-C during the transcription's set-up (a busy machine) stops Ipopt before its first
    # iteration; the result is then the initial guess's, as interrupted.
    assert result["iterations"] >= 0
    assert result["rows"] > 1
