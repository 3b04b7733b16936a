#include "dynamics/minimum_norm.hpp"

#include <Eigen/QR>

namespace lagrange::dynamics {

namespace {

Pattern identity(size_t n) {
  Pattern p(n);
  for (size_t j = 0; j < n; ++j) p[j] = {j, j};
  return p;
}

}  // namespace

MinimumNorm::MinimumNorm(size_t n, size_t m, const Pattern& J)
    : n_(n),
      m_(m),
      J_(J),
      normal_(n, m, identity(n), J, 1e-12),
      ones_(n, 1.0),
      zeros_(n, 0.0),
      lambda_(m) {}

// docs/theory.md §4.3, "Projecting when the drift matters": with M = I and h + Q = 0 the
// range-space solve gives λ = −(J Jᵀ)⁻¹ r and x = −Jᵀλ = Jᵀ (J Jᵀ)⁻¹ r.
void MinimumNorm::solve(const double* j_values, const double* r, double* x) {
  if (normal_.solve(ones_.data(), j_values, zeros_.data(), r, x, lambda_.data())) return;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(static_cast<long>(m_), static_cast<long>(n_));
  for (size_t e = 0; e < J_.size(); ++e)
    J(static_cast<long>(J_[e].first), static_cast<long>(J_[e].second)) = j_values[e];
  const Eigen::VectorXd solution = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(J).solve(
      Eigen::Map<const Eigen::VectorXd>(r, static_cast<long>(m_)));
  Eigen::Map<Eigen::VectorXd>(x, static_cast<long>(n_)) = solution;
}

}  // namespace lagrange::dynamics
