"""The stepper from Python: step for step one simulate call (bit for bit with dop853), a feedback
law written in Python against the same law written in the model file, and a zero-order-hold
controller that converges to that law at first order in its period."""

import math

import numpy as np
import pytest

import lagrange
from conftest import SOURCE_DIR

# The elbow manipulator of examples/elbow_manipulator.yaml with its joint torques set by a law.
ELBOW = (SOURCE_DIR / "examples" / "elbow_manipulator.yaml").read_text()
KP, KD, Q1_REF, Q2_REF = 30.0, 6.0, 0.9, -0.4
FILE_LAW = {"q1": f"-{KP}*(q1 - {Q1_REF}) - {KD}*der(q1)", "q2": f"-{KP}*(q2 - {Q2_REF}) - {KD}*der(q2)"}


def elbow(torques, inputs=""):
    text = ELBOW.replace("simulate: {t_end: 5, output_step: 0.01, rtol: 1e-10, atol: 1e-12}",
                         "simulate: {t_end: 2, output_step: 0.05, rtol: 1e-11, atol: 1e-13}")
    text = text.replace("type: revolute, axis: [0, 0, 1], initial: 0.3}",
                        f"type: revolute, axis: [0, 0, 1], initial: 0.3, torque: {torques['q1']}}}")
    text = text.replace("origin: {xyz: [L1, 0, 0]}, initial: 0.6}",
                        f"origin: {{xyz: [L1, 0, 0]}}, initial: 0.6, torque: {torques['q2']}}}")
    return lagrange.loads(inputs + text, label="<elbow>")


def elbow_external():
    return elbow({"q1": "tau1", "q2": "tau2"},
                 "inputs:\n  tau1: {value: 0, external: true}\n  tau2: {value: 0, external: true}\n")


def pd(q, v):
    return [-KP * (q[0] - Q1_REF) - KD * v[0], -KP * (q[1] - Q2_REF) - KD * v[1]]


@pytest.mark.parametrize("name", ["double_pendulum.yaml", "figure_eight.yaml"])
def test_stepper_equals_simulate_bit_for_bit(name, examples_dir):
    m = lagrange.load(str(examples_dir / name))
    run = m.simulate(t_end=1.5, output_step=0.05, integrator="dop853", compile="off")
    s = m.stepper(t_end=1.5, integrator="dop853", compile="off")
    for _ in range(len(run.t) - 1):
        s.step(0.05)
    assert s.t == 1.5
    stepped = s.trajectory()
    assert stepped.columns == run.columns
    assert np.array_equal(stepped.array, run.array)
    q, v = s.state
    assert np.array_equal(q, run.array[-1, 1:1 + len(q)])


def test_python_law_equals_the_law_in_the_file():
    one = elbow(FILE_LAW).simulate()
    m = elbow_external()
    s = m.stepper()
    assert s.inputs == ["tau1", "tau2"]
    s.set_law(lambda t, q, v: pd(q, v))
    for _ in range(len(one.t) - 1):
        s.step(0.05)
    run = s.trajectory()
    for c in ["q1", "q2", "q1_dot", "q2_dot"]:
        np.testing.assert_allclose(run[c], one[c], rtol=0, atol=1e-9)
    # the law brings the arm to rest where its torques balance gravity (no gravity compensation)
    q_end = np.array([one["q1"][-1], one["q2"][-1]])
    assert abs(one["q1_dot"][-1]) < 0.05 and abs(one["q2_dot"][-1]) < 0.05
    assert np.abs(elbow(FILE_LAW).forward(q_end, np.zeros(2))).max() < 0.5


def test_held_controller_converges_to_the_law_at_first_order():
    reference = elbow(FILE_LAW).simulate()
    errors = []
    for period in [0.01, 0.005]:
        s = elbow_external().stepper()
        for _ in range(round(2.0 / period)):
            q, v = s.state
            tau = pd(q, v)
            s.step(period, inputs={"tau1": tau[0], "tau2": tau[1]})
        q, _ = s.state
        errors.append(abs(q[0] - reference["q1"][-1]) + abs(q[1] - reference["q2"][-1]))
    # zero-order hold: error ∝ period
    assert 1.6 < errors[0] / errors[1] < 2.5, errors


def test_errors_keep_the_state():
    s = elbow_external().stepper()
    with pytest.raises(ValueError, match="'q1' is not an external input"):
        s.step(0.1, inputs={"q1": 1.0})
    s.step(0.1, inputs={"tau1": 0.5})
    t, (q, v) = s.t, s.state

    def failing(t, q, v):
        if t > 0.15:
            raise ZeroDivisionError("controller fault")
        return [0.0, 0.0]

    s.set_law(failing)
    with pytest.raises(ZeroDivisionError, match="controller fault"):
        s.step(0.1)
    assert s.t == t
    assert np.array_equal(s.state[0], q) and np.array_equal(s.state[1], v)
    s.set_law(None)
    s.step(0.1)
    assert math.isclose(s.t, 0.2)
    assert len(s.trajectory().t) == 3


@pytest.mark.parametrize("integrator", ["dop853", "rk4", "cvode"])
def test_a_law_cannot_step_its_own_stepper(integrator):
    # issue 37 item 8: once dop853 recorded times 0, 0.3, 0.1, -9.7, rk4 ran on to t = 12.6 and
    # cvode looped forever; now the inner call is refused and the outer one changes nothing
    s = elbow_external().stepper(integrator=integrator)
    s.step(0.05)
    t, (q, v) = s.t, s.state
    calls = []

    def reentrant(t, q, v):
        calls.append(t)
        s.step(0.1)
        return [0.0, 0.0]

    s.set_law(reentrant)
    with pytest.raises(RuntimeError, match="stepper in use"):
        s.step(0.05)
    assert calls
    assert s.t == t
    assert np.array_equal(s.state[0], q) and np.array_equal(s.state[1], v)
    assert len(s.trajectory().t) == 2
    s.set_law(None)
    s.step(0.05)
    assert math.isclose(s.t, 0.1)
    assert list(s.trajectory().t) == [0.0, 0.05, s.t]


def test_outputs_at_the_state(examples_dir):
    m = lagrange.load(str(examples_dir / "figure_eight.yaml"))
    s = m.stepper(t_end=0.05)
    s.step(0.05)
    run = m.simulate(t_end=0.05, output_step=0.05)
    assert s.outputs["wing.azimuth"] == run["wing.azimuth"][-1]
