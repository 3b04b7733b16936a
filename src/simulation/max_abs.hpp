#pragma once
// max |x_i|, the size of a residual vector in the run's checks.

#include <algorithm>
#include <cmath>
#include <vector>

namespace lagrange {

/// The largest |x_i| (0 for an empty x).
inline double max_abs(const std::vector<double>& x) {
  double r = 0.0;
  for (double v : x) r = std::max(r, std::abs(v));
  return r;
}

}  // namespace lagrange
