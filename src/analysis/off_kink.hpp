#pragma once
// States moved off a kink of the dynamics (|x| at x = 0), where their derivatives do not exist
// (docs/theory.md §5.6): the implicit integrators and the optimiser take a one-sided derivative
// there.

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "lagrange/analysis.hpp"

namespace lagrange::analysis_detail {

/// y (n values) with each moved by 1e-9 relative plus 1e-9 absolute, in a random direction: the
/// derivatives there are one of the one-sided ones at y.
inline std::vector<double> off_kink(const double* y, size_t n, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> moved(y, y + n);
  for (double& x : moved) x += 1e-9 * (std::abs(x) + 1.0) * unit(random);
  return moved;
}

inline bool all_finite(const double* begin, const double* end) {
  return std::all_of(begin, end, [](double x) { return std::isfinite(x); });
}

/// Calls eval(), and while the values it wrote to [begin, end) are not all finite (at most three
/// times), moves the n values at y off the kink, in place, and calls it again (fixed seed).
template <class Eval>
void eval_off_kink(double* y, size_t n, const double* begin, const double* end, Eval&& eval) {
  eval();
  if (all_finite(begin, end)) return;  // the common case: no generator to seed
  std::mt19937 random(5);
  for (int attempt = 0; attempt < 3 && !all_finite(begin, end); ++attempt) {
    const std::vector<double> moved = off_kink(y, n, random);
    std::copy(moved.begin(), moved.end(), y);
    eval();
  }
}

/// The implicit form's Jacobians at (t, y = (q, v)) and (a, λ); at a kink, those at y moved off
/// it (docs/theory.md §5.6).
ImplicitJacobian implicit_off_kink(const DynamicsJacobian& jac, Dynamics& dyn, double t,
                                   const double* y, const double* a, const double* lambda);

}  // namespace lagrange::analysis_detail
