"""Model.linearize and Model.trim from Python: the CLI's numbers, the pendulum's exact modes, a
trim against its closed form, and an LQR designed on the linear model that balances the
nonlinear cart-pole stepped from Python."""

import json
import math
import re
import subprocess

import numpy as np
import pytest

import lagrange

# A cart (mass M) with a pole (point mass m at length l), pushed by an external force F; theta = 0
# is upright, so the upright equilibrium is unstable.
CART_POLE = """
name: cart-pole
parameters: {M: 1.0, m: 0.2, l: 0.6, g: 9.81}
inputs:
  F: {value: 0, external: true}
coordinates:
  x: {initial: 0}
  theta: {initial: 0}
points:
  cart: [x, 0, 0]
  bob: [x + l*sin(theta), l*cos(theta), 0]
particles: {cart: M, bob: m}
gravity: [0, -g, 0]
generalized_forces: {x: F}
"""


def test_pendulum_modes_are_exact_and_match_the_cli(examples_dir, cli):
    m = lagrange.load(str(examples_dir / "pendulum.yaml"))
    lin = m.linearize(q=[0.0], v=[0.0])
    assert lin.states == ["theta", "theta_dot"]
    omega = math.sqrt(9.81 / 1.0)
    assert np.allclose(lin.A, [[0, 1], [-omega**2, 0]], atol=1e-14)
    assert len(lin.modes) == 1
    assert lin.modes[0]["frequency_hz"] == pytest.approx(omega / (2 * math.pi), rel=1e-14)
    assert lin.modes[0]["damping"] == pytest.approx(0.0, abs=1e-14)
    out = subprocess.run([str(cli), "linearize", str(examples_dir / "pendulum.yaml"), "--at",
                          "theta=0", "--format", "json"], check=True, capture_output=True, text=True)
    assert np.array_equal(np.array(json.loads(out.stdout)["A"]), lin.A)


def test_cartesian_pendulum_has_only_the_physical_modes(examples_dir):
    m = lagrange.load(str(examples_dir / "cartesian_pendulum.yaml"))
    lin = m.linearize(q=[0.0, -1.0], v=[0.0, 0.0])
    assert lin.A.shape == (2, 2)  # on the manifold: one coordinate and its rate
    eig = np.linalg.eigvals(lin.A)
    assert np.allclose(sorted(eig.imag), [-math.sqrt(9.81), math.sqrt(9.81)], rtol=1e-12)
    assert np.allclose(eig.real, 0, atol=1e-12)


def test_trim_finds_the_hanging_equilibrium():
    # A constant horizontal force F on the bob holds the pendulum at tan(theta) = F/(m g).
    m = lagrange.loads("parameters: {m: 1.0, l: 1.0, g: 9.81, F: 3.0}\n"
                       "coordinates: {theta: {initial: 0.1}}\n"
                       "points: {bob: [l*sin(theta), -l*cos(theta), 0]}\n"
                       "particles: {bob: m}\ngravity: [0, -g, 0]\nforces: [{point: bob, force: [F, 0, 0]}]\n",
                       label="<pendulum in a side force>")
    r = m.trim()
    assert r.q[0] == pytest.approx(math.atan2(3.0, 9.81), abs=1e-12)
    assert r.residual <= 1e-10
    assert np.array_equal(r.v, [0.0])
    with pytest.raises(ValueError, match="no coordinate 'phi'"):
        m.trim(free=["phi"])
    # The side force as the unknown with theta held at 0.3: F = m g tan(theta), one step.
    held = m.trim(q=[0.3], free=["F"])
    assert held.inputs["F"] == pytest.approx(9.81 * math.tan(0.3), rel=1e-12)
    assert held.iterations == 1 and held.q[0] == 0.3


def lqr_gain(A, B, Q, R, iterations=5000):
    """Discrete LQR gain by iterating the Riccati difference equation to its fixed point."""
    P = Q.copy()
    for _ in range(iterations):
        K = np.linalg.solve(R + B.T @ P @ B, B.T @ P @ A)
        P_next = Q + A.T @ P @ (A - B @ K)
        if np.max(np.abs(P_next - P)) < 1e-12 * np.max(np.abs(P)):
            break
        P = P_next
    return np.linalg.solve(R + B.T @ P @ B, B.T @ P @ A)


def test_lqr_on_the_linear_model_balances_the_nonlinear_cart_pole():
    m = lagrange.loads(CART_POLE, label="<cart-pole>")
    dt = 0.02
    lin = m.linearize(inputs=["F"], discrete=dt)
    assert lin.states == ["x", "theta", "x_dot", "theta_dot"]
    assert max(abs(e) for e in np.linalg.eigvals(lin.A)) > 1  # upright is unstable
    K = lqr_gain(lin.A, lin.B, np.diag([1.0, 10.0, 1.0, 1.0]), np.array([[0.1]]))
    assert max(abs(e) for e in np.linalg.eigvals(lin.A - lin.B @ K)) < 1  # stable, linear

    # The stepper starts from the file's state: tip the pole there.
    tipped = CART_POLE.replace("theta: {initial: 0}", "theta: {initial: 0.15}")
    m = lagrange.loads(tipped, label="<cart-pole tipped>")

    def fly(controlled):
        s = m.stepper(integrator="dop853", rtol=1e-9)
        x, largest = np.array([0.0, 0.15, 0.0, 0.0]), 0.15
        for _ in range(int(10 / dt)):
            u = float(-(K @ x)[0]) if controlled else 0.0
            s.step(dt, inputs={"F": u})
            q, v = s.state
            x = np.concatenate([q, v])
            largest = max(largest, abs(x[1]))
        return x, largest

    (balanced, tilt), (_, fall) = fly(True), fly(False)
    assert np.max(np.abs(balanced)) < 1e-3  # back upright and at rest over the origin
    assert tilt < 0.3
    assert fall > 1.5  # left alone, it falls over


# The heavy top in Euler angles (docs/theory.md §5.5): with the precession rate Ω and the spin s
# held, theta_ddot = 0 at (I1 - I3) Ω² cos θ - I3 s Ω + m g l = 0.
EULER_TOP = """
name: top in Euler angles
parameters: {m: 1.0, g: 9.81, l: 0.1, I1: 0.006, I3: 0.01}
coordinates:
  phi: {initial: 0, rate: 4.55}
  theta: {initial: 0.8, rate: 0}
  psi: {initial: 0, rate: 20}
kinetic: I1/2*(der(theta)^2 + der(phi)^2*sin(theta)^2) + I3/2*(der(psi) + der(phi)*cos(theta))^2
potential: m*g*l*cos(theta)
"""


def test_trim_holds_steady_rates():
    top = lagrange.loads(EULER_TOP, label="<top>")
    r = top.trim(steady=["phi_dot", "psi_dot"], tol=1e-12)
    I1, I3, mgl, W, s = 0.006, 0.01, 9.81 * 0.1, 4.55, 20.0
    c = (I3 * s * W - mgl) / ((I1 - I3) * W * W)
    names = r.coordinates
    assert r.q[names.index("theta")] == pytest.approx(math.acos(c), abs=1e-9)
    assert r.v[names.index("phi")] == 4.55 and r.v[names.index("psi")] == 20.0
    assert r.drift == pytest.approx(0.0, abs=1e-12)  # phi and psi are cyclic
    assert not r.pseudo_transient
    with pytest.raises(ValueError, match="no rate 'omega'"):
        top.trim(steady=["omega"])


def test_jacobian_matches_differences_and_the_implicit_form():
    # A Cartesian pendulum in a side force: one constraint, so a = a(q, v) through the KKT system.
    m = lagrange.loads("parameters: {m: 1.0, l: 1.0, g: 9.81, F: 3.0}\n"
                       "coordinates: {x: {initial: 0.6, rate: 0.3}, y: {initial: -0.8, rate: 0.2}}\n"
                       "points: {bob: [x, y, 0]}\nparticles: {bob: m}\ngravity: [0, -g, 0]\n"
                       "forces: [{point: bob, force: [F, 0, 0]}]\n"
                       "constraints: {rod: x^2 + y^2 - l^2}\n", label="<cartesian pendulum>")
    J = m.jacobian(inputs=["F"])
    q, v = J.q, J.v
    h = 1e-6
    for k in range(2):
        dq = np.zeros(2)
        dq[k] = h
        fd = (m.forward(q + dq, v)[0] - m.forward(q - dq, v)[0]) / (2 * h)
        assert np.allclose(J.a_q[:, k], fd, atol=1e-7)
        fd = (m.forward(q, v + dq)[0] - m.forward(q, v - dq)[0]) / (2 * h)
        assert np.allclose(J.a_v[:, k], fd, atol=1e-7)
    assert J.a_w.shape == (2, 1) and J.inputs == ["F"]
    # d(a, lam)/d(q, v, F) = -K^-1 Phi_x: the implicit form's sparse Jacobians give the same.
    X = -np.linalg.solve(J.K, J.Phi_x)
    assert np.allclose(X[:2], np.hstack([J.a_q, J.a_v, J.a_w]), atol=1e-12)


# A pendulum at rest at theta = 0.3 with quadratic drag, on its bob or on theta.
DRAG_PENDULUM = """
parameters: {m: 1.0, l: 1.0, g: 9.81, c: 0.7}
coordinates: {theta: {initial: 0.3, rate: 0}}
points: {bob: [l*sin(theta), -l*cos(theta), 0]}
particles: {bob: m}
gravity: [0, -g, 0]
"""


def test_quadratic_drag_at_rest_has_the_undamped_derivatives():
    # docs/theory.md §5.1, "Limits": d(|v| v)/dv = 0 at v = 0, 0/0 on the tape as written.
    for drag in ("forces: [{point: bob, force: -c*norm(vel(bob))*vel(bob)}]\n",
                 "generalized_forces: {theta: -c*der(theta)*abs(der(theta))}\n"):
        m = lagrange.loads(DRAG_PENDULUM + drag, label="<drag pendulum>")
        J = m.jacobian()
        assert J.a_v[0, 0] == 0.0
        assert J.a_q[0, 0] == pytest.approx(-9.81 * math.cos(0.3), rel=1e-12)
        assert np.all(np.isfinite(J.Phi_x))
        assert np.allclose(m.linearize().A, [[0, 1], [-9.81 * math.cos(0.3), 0]], rtol=0, atol=1e-12)
    # |theta_dot| alone has no derivative at 0: raised, never NaN.
    m = lagrange.loads(DRAG_PENDULUM + "generalized_forces: {theta: -c*abs(der(theta))}\n",
                       label="<dry friction>")
    with pytest.raises(lagrange.AnalysisError, match="not differentiable"):
        m.jacobian()


def test_trim_tolerance_is_the_command_lines(cli):
    shown = subprocess.run([str(cli), "trim", "--help"], capture_output=True, text=True).stdout
    command_line = float(re.search(r"max \|acceleration\| \(default ([-+.e0-9]+)\)", shown)[1])
    m = lagrange.loads(DRAG_PENDULUM, label="<pendulum>")
    python = float(re.search(r"tol: float = ([-+.e0-9]+)", m.trim.__doc__)[1])
    assert python == command_line


SIDE_FORCE = """
name: pendulum in a side force
parameters: {m: 1.0, l: 1.0, g: 9.81, F: 0.0}
coordinates: {theta: {initial: 0.3}}
points: {bob: [l*sin(theta), -l*cos(theta), 0]}
particles: {bob: m}
gravity: [0, -g, 0]
forces: [{point: bob, force: [F, 0, 0]}]
"""


def test_linearize_trims_first_and_takes_values_as_the_cli(cli, tmp_path):
    # F = m g tan(theta) holds the pendulum at theta = 0.3; there
    # theta'' = (F cos(theta) - m g sin(theta))/(m l) has d/dtheta = -g/(l cos(theta)).
    path = tmp_path / "side_force.yaml"
    path.write_text(SIDE_FORCE)
    m = lagrange.load(str(path))
    trimmed = m.linearize(inputs=["F"], at_trim=True, free=["F"])
    F = trimmed.trim.inputs["F"]
    assert F == pytest.approx(9.81 * math.tan(0.3), rel=1e-10)
    assert trimmed.A[1, 0] == pytest.approx(-9.81 / math.cos(0.3), rel=1e-10)
    assert trimmed.B[1, 0] == pytest.approx(math.cos(0.3), rel=1e-12)
    out = subprocess.run([str(cli), "linearize", str(path), "--at-trim", "--free", "F",
                          "--inputs", "F", "--format", "json"],
                         check=True, capture_output=True, text=True)
    j = json.loads(out.stdout)
    assert j["trim"]["inputs"]["F"] == F
    assert np.array_equal(np.array(j["A"]), trimmed.A)
    assert np.array_equal(np.array(j["B"]), trimmed.B)
    # The same operating point given as a value, and on the command line as --set.
    given = m.linearize(inputs=["F"], values={"F": F})
    assert np.array_equal(given.A, trimmed.A)
    assert given.trim is None
    out = subprocess.run([str(cli), "linearize", str(path), "--set", f"F={F!r}", "--inputs", "F",
                          "--format", "json"], check=True, capture_output=True, text=True)
    assert np.array_equal(np.array(json.loads(out.stdout)["A"]), given.A)
    # Without them, the F = 0 matrices: A[1, 0] = -g cos(theta).
    assert m.linearize().A[1, 0] == pytest.approx(-9.81 * math.cos(0.3), rel=1e-12)
    with pytest.raises(ValueError, match="give at_trim=True"):
        m.linearize(free=["F"])
    with pytest.raises(ValueError, match=r"values: no parameter or model input 'G' \(parameters: "):
        m.linearize(values={"G": 1.0})
