"""Mistakes raise Python exceptions with the library's messages and locations."""

import pytest

import lagrange

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


def test_simulation_error_carries_the_partial_run():
    m = lagrange.loads(SQRT_THROUGH_ZERO)
    with pytest.raises(lagrange.SimulationError, match="not finite") as info:
        m.simulate()
    e = info.value
    assert 0.05 < e.time < 0.2
    run = e.run
    assert run.status == "failed" and run.message == str(e)
    assert 5 < len(run) < 20 and run.t[-1] <= e.time
    assert (run["x"] > 0).all()
