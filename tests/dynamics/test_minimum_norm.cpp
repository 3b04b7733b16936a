// The pattern-fixed minimum-norm solve x = Jᵀ(J Jᵀ)⁻¹ r against the dense pseudo-inverse
// (complete orthogonal decomposition), on a banded J like a chain's and on one with a redundant
// row (where the normal equations are singular and the dense fallback answers).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "dynamics/minimum_norm.hpp"

namespace lagrange::dynamics {
namespace {

Eigen::MatrixXd dense(size_t m, size_t n, const Pattern& p, const std::vector<double>& values) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(long(m), long(n));
  for (size_t e = 0; e < p.size(); ++e) J(long(p[e].first), long(p[e].second)) = values[e];
  return J;
}

TEST(MinimumNorm, BandedRowsMatchThePseudoInverse) {
  // Row r touches columns 3r … 3r + 5 (rods between consecutive nodes of a chain).
  const size_t m = 30, n = 3 * m + 3;
  Pattern p;
  for (size_t r = 0; r < m; ++r)
    for (size_t c = 3 * r; c < 3 * r + 6; ++c) p.emplace_back(r, c);
  MinimumNorm solver(n, m, p);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (int trial = 0; trial < 3; ++trial) {  // new values on the same pattern
    std::vector<double> values(p.size()), r(m), x(n);
    for (double& v : values) v = U(rng);
    for (double& v : r) v = U(rng);
    solver.solve(values.data(), r.data(), x.data());
    const Eigen::MatrixXd J = dense(m, n, p, values);
    const Eigen::VectorXd expected = J.completeOrthogonalDecomposition().solve(
        Eigen::Map<const Eigen::VectorXd>(r.data(), long(m)));
    const Eigen::Map<const Eigen::VectorXd> got(x.data(), long(n));
    EXPECT_LT((got - expected).norm(), 1e-12 * expected.norm()) << trial;
  }
}

TEST(MinimumNorm, RedundantRowsFallBackToThePseudoInverse) {
  // Rows 0 and 2 are equal: J Jᵀ is singular, J x = r consistent (r₀ = r₂).
  const Pattern p = {{0, 0}, {0, 1}, {1, 1}, {1, 2}, {2, 0}, {2, 1}};
  const std::vector<double> values = {1.0, 2.0, -1.0, 0.5, 1.0, 2.0};
  const std::vector<double> r = {0.3, -0.2, 0.3};
  std::vector<double> x(3);
  MinimumNorm solver(3, 3, p);
  solver.solve(values.data(), r.data(), x.data());
  const Eigen::MatrixXd J = dense(3, 3, p, values);
  const Eigen::VectorXd expected =
      J.completeOrthogonalDecomposition().solve(Eigen::Map<const Eigen::VectorXd>(r.data(), 3));
  for (long i = 0; i < 3; ++i) EXPECT_NEAR(x[size_t(i)], expected[i], 1e-14) << i;
  EXPECT_NEAR((J * Eigen::Map<const Eigen::VectorXd>(x.data(), 3))[1], r[1], 1e-14);
}

}  // namespace
}  // namespace lagrange::dynamics
