#pragma once
// The planar double pendulum (point masses m1, m2 on massless rods l1, l2, absolute angles) in
// closed form, for the long-run energy tests of the integrators.

#include <cmath>

#include "lagrange/integrator.hpp"

namespace lagrange::test {

/// y = (θ1, θ2, ω1, ω2); the textbook equations solved for the angular accelerations.
struct DoublePendulum {
  double m1 = 1.0, m2 = 1.0, l1 = 1.0, l2 = 1.0, g = 9.81;

  OdeProblem problem() const {
    const DoublePendulum p = *this;
    return {4, [p](double, const double* y, double* ydot) {
              const double d = y[1] - y[0], c = std::cos(d), s = std::sin(d);
              const double w1 = y[2], w2 = y[3], M = p.m1 + p.m2;
              const double den1 = M * p.l1 - p.m2 * p.l1 * c * c;
              const double den2 = p.l2 / p.l1 * den1;
              ydot[0] = w1;
              ydot[1] = w2;
              ydot[2] = (p.m2 * p.l1 * w1 * w1 * s * c + p.m2 * p.g * std::sin(y[1]) * c +
                         p.m2 * p.l2 * w2 * w2 * s - M * p.g * std::sin(y[0])) /
                        den1;
              ydot[3] =
                  (-p.m2 * p.l2 * w2 * w2 * s * c +
                   M * (p.g * std::sin(y[0]) * c - p.l1 * w1 * w1 * s - p.g * std::sin(y[1]))) /
                  den2;
            },
            {}};  // no Jacobian: Newton matrices from difference quotients
  }
  /// T + U at y.
  double energy(const double* y) const {
    const double M = m1 + m2;
    const double T = 0.5 * M * l1 * l1 * y[2] * y[2] + 0.5 * m2 * l2 * l2 * y[3] * y[3] +
                     m2 * l1 * l2 * y[2] * y[3] * std::cos(y[0] - y[1]);
    const double U = -M * g * l1 * std::cos(y[0]) - m2 * g * l2 * std::cos(y[1]);
    return T + U;
  }
};

}  // namespace lagrange::test
