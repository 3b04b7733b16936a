"""The scripts in examples/python run and write what they say."""

import os
import subprocess
import sys

import lagrange
from conftest import SOURCE_DIR

SCRIPTS = SOURCE_DIR / "examples" / "python"


def env_importing_lagrange():
    # The scripts import the module this test imported, whatever the working directory.
    package_parent = os.path.dirname(os.path.dirname(os.path.abspath(lagrange.__file__)))
    path = [package_parent] + [p for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p]
    return dict(os.environ, PYTHONPATH=os.pathsep.join(path), MPLBACKEND="Agg")


def run_script(name, *args, cwd):
    result = subprocess.run([sys.executable, str(SCRIPTS / name), *map(str, args)], cwd=cwd,
                            env=env_importing_lagrange(), capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    return result.stdout


def test_derive_script(tmp_path):
    stdout = run_script("derive.py", tmp_path, cwd=tmp_path)
    assert "Mass matrix M(q)" in stdout
    assert "\\ddot{\\theta}_{1}" in (tmp_path / "double_pendulum.tex").read_text()


def test_simulate_plot_script(tmp_path):
    stdout = run_script("simulate_plot.py", tmp_path, cwd=tmp_path)
    png = (tmp_path / "elastic_pendulum.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10000
    assert stdout.count("501 samples") == 2


def test_forward_batch_script(tmp_path):
    stdout = run_script("forward_batch.py", cwd=tmp_path)
    assert "10201 states" in stdout
    # (0, 0), (0, ±π), (±π, 0), (±π, ±π): the grid's corners and edges at rest
    assert "(0.0, 0.0)" in stdout


def test_controller_in_loop_script(tmp_path):
    stdout = run_script("controller_in_loop.py", 10, cwd=tmp_path)
    assert "200 control steps of 0.05 s" in stdout
    # the Python law flies the file's orbit: the azimuth stays within the loops' ±0.5 rad
    line = next(x for x in stdout.splitlines() if x.startswith("azimuth range"))
    low, high = (float(x) for x in line.split("Python law ")[1].split(" rad")[0].split(" .. "))
    assert -0.7 < low < -0.2 and 0.2 < high < 0.7, line
