#pragma once
// States moved off a kink of the dynamics (|x| at x = 0), where their derivatives do not exist
// (docs/theory.md §5.6).

#include <cmath>
#include <random>
#include <vector>

namespace lagrange::analysis_detail {

/// y (n values) with each moved by 1e-9 relative plus 1e-9 absolute, in a random direction: the
/// derivatives there are one of the one-sided ones at y.
inline std::vector<double> off_kink(const double* y, size_t n, std::mt19937& random) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> moved(y, y + n);
  for (double& x : moved) x += 1e-9 * (std::abs(x) + 1.0) * unit(random);
  return moved;
}

}  // namespace lagrange::analysis_detail
