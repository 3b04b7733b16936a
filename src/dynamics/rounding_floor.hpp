#pragma once
// The level below which a residual built from terms of size |∂F/∂x| |x| cannot be computed
// (docs/theory.md §4.3 for the constraints, §5.5 for trim's accelerations).

#include <Eigen/Dense>
#include <limits>

namespace lagrange {

/// 16 ε max_r Σ_j |J_rj| |x_j|: the rounding of x alone moves F = F(x) by about ε Σ_j |J_rj| |x_j|
/// (exactly the size of the terms of a distance constraint ½(|d|² − ℓ²)), so below a few ulps of
/// that no step can reduce |F|.
inline double rounding_floor(const Eigen::MatrixXd& J, const Eigen::VectorXd& x) {
  const Eigen::VectorXd terms = J.cwiseAbs() * x.cwiseAbs();
  return 16 * std::numeric_limits<double>::epsilon() * (terms.size() ? terms.maxCoeff() : 0.0);
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
