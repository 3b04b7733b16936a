"""compile="on" with a C compiler that never returns (issue 37 item 10): its time limit stops it
with a RuntimeWarning and the interpreter runs; Ctrl-C while it runs raises KeyboardInterrupt at
once instead of waiting forever, and leaves no compiler running."""

import os
import signal
import subprocess
import sys
import time

import pytest

import lagrange


def hung_compiler(tmp_path):
    """A "compiler" that writes its process id to cc.pid, then waits forever on a child."""
    script = tmp_path / "hung-cc"
    pid = tmp_path / "cc.pid"
    script.write_text(f"#!/bin/sh\necho $$ > '{pid}.part'\nmv '{pid}.part' '{pid}'\nsleep 600 &\nwait\n")
    script.chmod(0o700)
    return script, pid


def wait_for(path, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        if path.exists() and path.read_text().strip():
            return int(path.read_text())
        time.sleep(0.02)
    pytest.fail(f"{path} never appeared")


def running_in_group(group):
    """The processes of `group` that run (zombies, left for whoever reaps orphans, do not)."""
    found = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit():
            continue
        try:
            with open(f"/proc/{entry}/stat") as f:
                stat = f.read()
        except OSError:
            continue
        state, _ppid, pgrp = stat[stat.rfind(")") + 2:].split()[:3]
        if int(pgrp) == group and state != "Z":
            found.append(int(entry))
    return found


def group_gone(group):
    for _ in range(100):
        if not running_in_group(group):
            return True
        time.sleep(0.02)
    return False


def test_a_hung_compiler_is_stopped_and_the_interpreter_runs(examples_dir, tmp_path, monkeypatch):
    script, pid = hung_compiler(tmp_path)
    monkeypatch.setenv("LAGRANGE_CC", str(script))
    monkeypatch.setenv("LAGRANGE_CACHE_DIR", str(tmp_path / "cache"))
    monkeypatch.setenv("LAGRANGE_CC_TIMEOUT", "1")
    model = lagrange.load(str(examples_dir / "pendulum.yaml"))
    start = time.monotonic()
    with pytest.warns(RuntimeWarning, match="ran for more than 1 s and was stopped"):
        run = model.simulate(t_end=0.5, compile="on")
    assert time.monotonic() - start < 30
    assert len(run) > 1
    assert group_gone(int(pid.read_text()))
    assert not list((tmp_path / "cache").rglob("*.c"))


def test_ctrl_c_while_compiling_raises_keyboard_interrupt(examples_dir, tmp_path):
    script, pid = hung_compiler(tmp_path)
    env = dict(os.environ, LAGRANGE_CC=str(script), LAGRANGE_CACHE_DIR=str(tmp_path / "cache"))
    code = (
        "import lagrange\n"
        f"m = lagrange.load({str(examples_dir / 'pendulum.yaml')!r})\n"
        "try:\n"
        "    m.simulate(t_end=0.5, compile='on')\n"
        "except KeyboardInterrupt:\n"
        "    print('KeyboardInterrupt caught')\n"
    )
    child = subprocess.Popen(
        [sys.executable, "-c", code], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
        text=True)
    try:
        group = wait_for(pid, 60)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        out, err = child.communicate(timeout=30)
    finally:
        child.kill()
    assert time.monotonic() - sent < 5
    assert "KeyboardInterrupt caught" in out, err
    assert child.returncode == 0, err
    assert group_gone(group)
    assert not list((tmp_path / "cache").rglob("*.c"))
