#pragma once
// The coefficients of DOP853 (Dormand–Prince 8(5,3) with a continuous extension of order 7), as
// Hairer, Nørsett and Wanner publish them; the stepper is src/integrate/dop853.cpp.

#include <array>
#include <vector>

#include "integrate/erk_coefficients.hpp"

namespace lagrange::integration {

/// DOP853: 12 stages of order 8 (stage 13 is f at the step's end, reused by the next step), two
/// error estimates (fifth and third order) and three more stages for the dense output.
struct Dop853Coefficients {
  ButcherCoefficients main;     ///< c, A, b (order 8) and the fifth-order embedding d = b − e5
  std::vector<double> e5;       ///< b minus the fifth-order weights (the error estimate)
  std::vector<double> b3;       ///< third-order weights, on stages 1, 9 and 12
  std::vector<double> e3;       ///< b − b3 (the second error estimate)
  std::vector<double> extra_c;  ///< nodes of dense-output stages 14–16
  std::vector<std::vector<double>> extra_a;  ///< their rows, over stages 1–13 (1–15)
  std::array<std::vector<double>, 4> dense;  ///< the interpolant's last four coefficients, over
                                             ///< stages 1–16
};

/// The table, built once.
const Dop853Coefficients& dop853();

}  // namespace lagrange::integration
