#pragma once
// The heavy symmetric top in Euler angles (φ precession, θ nutation, ψ spin), the steady-state
// oracle of test_steady_state.cpp (derived there) and of the CLI's `trim --steady` tests.

namespace lagrange::testing {

inline const char* const kEulerTop = R"(
name: top in Euler angles
parameters: {m: 1.0, g: 9.81, l: 0.1, I1: 0.006, I3: 0.01}
coordinates:
  phi: {initial: 0, rate: 4.55}
  theta: {initial: 0.8, rate: 0}
  psi: {initial: 0, rate: 20}
kinetic: I1/2*(der(theta)^2 + der(phi)^2*sin(theta)^2) + I3/2*(der(psi) + der(phi)*cos(theta))^2
potential: m*g*l*cos(theta)
)";

}  // namespace lagrange::testing
