// The envelope L D Lᵀ against Eigen's dense LLT on banded SPD matrices.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "dynamics/envelope_cholesky.hpp"

namespace lagrange::dynamics {
namespace {

TEST(EnvelopeCholesky, SolvesBandedSystemsLikeDenseLlt) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  for (size_t m : {1u, 2u, 7u, 40u}) {
    for (size_t band : {0u, 1u, 3u}) {
      // A = B Bᵀ + m I with B banded: SPD with the same envelope as B Bᵀ (bandwidth 2·band).
      Eigen::MatrixXd B = Eigen::MatrixXd::Zero(static_cast<long>(m), static_cast<long>(m));
      for (size_t i = 0; i < m; ++i)
        for (size_t j = (i > band ? i - band : 0); j <= i; ++j) B(long(i), long(j)) = U(rng);
      const Eigen::MatrixXd A =
          B * B.transpose() + double(m) * Eigen::MatrixXd::Identity(long(m), long(m));
      std::vector<size_t> first(m);
      for (size_t i = 0; i < m; ++i) first[i] = i > 2 * band ? i - 2 * band : 0;
      EnvelopeCholesky chol(first);
      for (size_t i = 0; i < m; ++i)
        for (size_t j = first[i]; j <= i; ++j)
          chol.values()[chol.index(i, j)] = A(long(i), long(j));
      ASSERT_TRUE(chol.factorize());
      Eigen::VectorXd b = Eigen::VectorXd::Random(long(m));
      const Eigen::VectorXd expected = A.llt().solve(b);
      chol.solve(b.data());
      EXPECT_LT((b - expected).norm(), 1e-12 * expected.norm()) << m << " " << band;
      // Five right-hand sides at once, row-major (the differentiated KKT system's form).
      using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
      RowMajor R = RowMajor::Random(long(m), 5);
      const Eigen::MatrixXd X = A.llt().solve(Eigen::MatrixXd(R));
      chol.solve_rows(R.data(), 5);
      EXPECT_LT((Eigen::MatrixXd(R) - X).norm(), 1e-12 * X.norm()) << m << " " << band;
    }
  }
}

TEST(EnvelopeCholesky, RejectsSingularMatrices) {
  EnvelopeCholesky chol({0, 0});
  // [[1, 1], [1, 1]] is singular.
  chol.values()[chol.index(0, 0)] = 1;
  chol.values()[chol.index(1, 0)] = 1;
  chol.values()[chol.index(1, 1)] = 1;
  EXPECT_FALSE(chol.factorize());
}

}  // namespace
}  // namespace lagrange::dynamics
