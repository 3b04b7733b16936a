#pragma once
// Test problems with closed-form solutions, shared by the integrator tests.

#include <cmath>

#include "lagrange/integrator.hpp"

namespace lagrange::test {

/// x'' = −ω² x as y = (x, v); from (x0, v0) at t0: x = x0 cos ωs + v0/ω sin ωs, s = t − t0.
struct Oscillator {
  double omega = 2.0;

  /// The first-order problem y' = (v, −ω² x), with its exact Jacobian [0 1; −ω² 0].
  OdeProblem problem() const {
    const double w2 = omega * omega;
    OdeProblem p;
    p.size = 2;
    p.rhs = [w2](double, const double* y, double* ydot) {
      ydot[0] = y[1];
      ydot[1] = -w2 * y[0];
    };
    p.jacobian.column_starts = {0, 1, 2};
    p.jacobian.rows = {1, 0};
    p.jacobian.values = [w2](double, const double*, double* values) {
      values[0] = -w2;
      values[1] = 1.0;
    };
    return p;
  }
  /// Closed-form x(t) from (x0, v0) at t0.
  double x(double t, double t0, double x0, double v0) const {
    const double s = omega * (t - t0);
    return x0 * std::cos(s) + v0 / omega * std::sin(s);
  }
  /// Closed-form v(t) from (x0, v0) at t0.
  double v(double t, double t0, double x0, double v0) const {
    const double s = omega * (t - t0);
    return -x0 * omega * std::sin(s) + v0 * std::cos(s);
  }
};

/// Options for `method` with the given tolerances.
inline IntegratorOptions options_for(const char* method, double rtol = 1e-8, double atol = 1e-10) {
  IntegratorOptions options;
  options.method = method;
  options.rtol = rtol;
  options.atol = atol;
  return options;
}

}  // namespace lagrange::test
