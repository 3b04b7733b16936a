#pragma once
// A drum reeling a hanging tether with a payload under a constant motor torque τ: the tether is
// straight, everything on the line moves at ℓ̇, so (J/R² + μL + m_p) ℓ̈ = m_p g + μ g ℓ + τ/R
// (docs/theory.md §4.6). Shared by the constraint-accuracy and the load-column tests.

#include <cmath>
#include <string>

namespace lagrange::testing::winch_payload {

constexpr double kR = 0.2, kJ = 0.05, kMu = 0.4, kL = 30, kG = 9.81, kMp = 2.0, kTau = -0.5;
constexpr double kEll0 = 1.0, kRate0 = 0.5;

/// ℓ(t) of the closed form.
inline double closed_form(double t) {
  const double me = kJ / (kR * kR) + kMu * kL + kMp, w = std::sqrt(kMu * kG / me);
  const double b = (kMp * kG + kTau / kR) / me;
  return (kEll0 + b / (w * w)) * std::cosh(w * t) + kRate0 / w * std::sinh(w * t) - b / (w * w);
}

/// ℓ̈ at the reeled-out length ℓ.
inline double acceleration(double ell) {
  return ((kMp + kMu * ell) * kG + kTau / kR) / (kJ / (kR * kR) + kMu * kL + kMp);
}

inline const char* parameters() {
  return "parameters: {R: 0.2, J: 0.05, mu: 0.4, L: 30, g: 9.81, mp: 2.0, tau: -0.5}\n";
}

/// The model file, a lumped line of `segments` segments (the drum's line is `reel`).
inline std::string model(int segments = 6, const std::string& reel =
                                               "torque: tau, initial: {reeled_out: 1, rate: 0.5, "
                                               "fixed: true}") {
  return std::string("name: winch with payload\n") + parameters() + R"(gravity: [0, 0, -g]
coordinates:
  px: {initial: 0}
  py: {initial: 0}
  pz: {initial: -1, rate: -0.5}
points: {load: [px, py, pz]}
particles: {load: mp}
winches:
  drum: {tether: line, radius: R, inertia: J, total_length: L, )" +
         reel + R"(}
tethers:
  line: {between: [[0, 0, 0], load], segments: )" +
         std::to_string(segments) + R"(, mass_per_length: mu}
simulate: {t_end: 4, output_step: 0.01}
)";
}

}  // namespace lagrange::testing::winch_payload
