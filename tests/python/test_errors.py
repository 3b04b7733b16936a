"""Mistakes raise Python exceptions with the library's messages and locations."""

import subprocess

import numpy as np
import pytest

import lagrange
from test_cli_identical import read_csv

BAD_EXPRESSION = """name: bad
coordinates:
  x: {initial: 1}
kinetic: der(x)^2/2
potential: x^2 +* 3
"""

SQRT_THROUGH_ZERO = """name: sqrt through zero
coordinates:
  x: {initial: 1, rate: -10}
kinetic: der(x)^2/2
potential: x^(5/2)
simulate: {t_end: 1, output_step: 0.01}
"""


def test_model_error_carries_the_location():
    with pytest.raises(lagrange.ModelError) as info:
        lagrange.loads(BAD_EXPRESSION, label="bad.yaml")
    e = info.value
    assert isinstance(e, ValueError)
    assert e.file == "bad.yaml"
    assert e.line == 5 and e.column > 10
    assert str(e).startswith(f"bad.yaml:5:{e.column}: ")
    assert e.detail in str(e)


def test_missing_file_is_a_model_error(tmp_path):
    path = str(tmp_path / "absent.yaml")
    with pytest.raises(lagrange.ModelError, match="cannot open the model file") as info:
        lagrange.load(path)
    assert info.value.file == path and info.value.line == 0


def test_unknown_parameter_in_set_is_a_value_error(examples_dir):
    with pytest.raises(ValueError, match="set: .*nope") as info:
        lagrange.load(str(examples_dir / "pendulum.yaml"), set={"nope": 1.0})
    assert not isinstance(info.value, lagrange.ModelError)


def test_simulation_error_carries_the_partial_run(cli, tmp_path):
    path = tmp_path / "sqrt.yaml"
    path.write_text(SQRT_THROUGH_ZERO)
    m = lagrange.load(str(path))
    with pytest.raises(lagrange.SimulationError, match="not finite") as info:
        m.simulate()
    e = info.value
    assert isinstance(e, RuntimeError)
    assert 0.05 < e.time < 0.2  # x = 1 - 10 t (and faster) reaches 0 where x^(5/2) stops
    run = e.run
    assert run.status == "failed" and run.message == str(e) and run.failure_time == e.time
    assert len(run) > 1 and run.t[-1] <= e.time
    assert (run["x"] > 0).all()
    # The rows the command keeps in its CSV when it fails (exit 3), bit for bit.
    out = tmp_path / "out.csv"
    result = subprocess.run([cli, "simulate", str(path), "-o", str(out), "-q"], capture_output=True)
    assert result.returncode == 3
    header, table = read_csv(out)
    assert header == run.columns and np.array_equal(table, run.array)


def test_forward_raises_simulation_error_for_a_singular_mass_matrix():
    m = lagrange.loads("name: fading mass\ncoordinates:\n  x: {initial: 0, rate: 1}\n"
                       "kinetic: (1 - t)*der(x)^2/2\n")
    assert m.forward([0.0], [1.0], t=0.5)[0] == pytest.approx(2.0)  # (1 - t) a = v
    with pytest.raises(lagrange.SimulationError) as info:
        m.forward([0.0], [1.0], t=1.5)
    assert info.value.time == 1.5 and info.value.run is None
