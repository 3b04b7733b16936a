#pragma once
// The level below which a residual built from terms of size |∂F/∂x| |x| cannot be computed
// (docs/theory.md §4.3 for the constraints, §5.5 for trim's accelerations).

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

namespace lagrange {

/// 16 ε max_r Σ_j |J_rj| |x_j|: the rounding of x alone moves F = F(x) by about ε Σ_j |J_rj| |x_j|
/// (exactly the size of the terms of a distance constraint ½(|d|² − ℓ²)), so below a few ulps of
/// that no step can reduce |F|.
inline double rounding_floor(const Eigen::MatrixXd& J, const Eigen::VectorXd& x) {
  const Eigen::VectorXd terms = J.cwiseAbs() * x.cwiseAbs();
  return 16 * std::numeric_limits<double>::epsilon() * (terms.size() ? terms.maxCoeff() : 0.0);
}

/// The same for a sparse J given by its (row, column) pattern and values; `terms` (one per row of
/// J) is the caller's scratch.
inline double rounding_floor(const std::vector<std::pair<size_t, size_t>>& pattern,
                             const double* values, const double* x, std::vector<double>& terms) {
  std::fill(terms.begin(), terms.end(), 0.0);
  for (size_t e = 0; e < pattern.size(); ++e)
    terms[pattern[e].first] += std::abs(values[e]) * std::abs(x[pattern[e].second]);
  double largest = 0.0;
  for (const double t : terms) largest = std::max(largest, t);
  return 16 * std::numeric_limits<double>::epsilon() * largest;
}

/// ε max_r (Σ_j (J_rj x_j)²)^½: the rounding of x alone, with the roundings of the x_j
/// independent and so adding in quadrature — for a dense J (accelerations that depend on every
/// coordinate) the sum of |J_rj| |x_j| over hundreds of columns overstates them. The
/// caller scales it by how many roundings the evaluation adds.
inline double rounding_level(const Eigen::MatrixXd& J, const Eigen::VectorXd& x) {
  const Eigen::VectorXd terms = (J * x.cwiseAbs().asDiagonal()).rowwise().norm();
  return std::numeric_limits<double>::epsilon() * (terms.size() ? terms.maxCoeff() : 0.0);
}

}  // namespace lagrange
