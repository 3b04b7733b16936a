// The pattern-fixed range-space KKT solve against a dense factorisation of the same KKT
// system, state after state on one solver object (the patterns worked out once, the values
// new each call): a kite on a tether (a free body's 3×3 inertia block at the end of a chain)
// and a bridled kite (three lines from the body to a knot: a branching constraint graph).

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "dynamics/sparse_range_space.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

// The dynamics tape's outputs at (t, q, v) and γ = −c − 2αĊ − α²C, evaluated by the interpreter
// on the unspecialised tape (independently of Dynamics' own evaluation).
struct KktValues {
  std::vector<double> out, gamma;
};

KktValues kkt_values(Dynamics& dyn, double t, const std::vector<double>& q,
                     const std::vector<double>& v) {
  const CompiledModel& cm = dyn.model();
  std::vector<double> qd(cm.nq), a(cm.nv), lambda(cm.m);
  dyn.forward(t, q.data(), v.data(), qd.data(), a.data(), lambda.data());  // loads the inputs
  KktValues k;
  k.out.assign(cm.dynamics.num_outputs(), 0.0);
  std::vector<double> work(cm.dynamics.work_size() + 1);
  cm.dynamics.eval(dyn.last_inputs().data(), k.out.data(), work.data());
  const double alpha = dyn.baumgarte();
  for (size_t r = 0; r < cm.m; ++r)
    k.gamma.push_back(-k.out[cm.c_out() + r] - 2 * alpha * k.out[cm.Cdot_out() + r] -
                      alpha * alpha * k.out[cm.C_out() + r]);
  return k;
}

// [M Gᵀ; G 0][a; λ] = [h + Q; γ] by a dense Householder QR with column pivoting.
Eigen::VectorXd dense_kkt(const CompiledModel& cm, const KktValues& k) {
  const long n = static_cast<long>(cm.nv), m = static_cast<long>(cm.m);
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + m, n + m);
  for (size_t e = 0; e < cm.M_pattern.size(); ++e) {
    const auto [i, j] = cm.M_pattern[e];
    K(long(i), long(j)) = K(long(j), long(i)) = k.out[e];
  }
  for (size_t e = 0; e < cm.G_pattern.size(); ++e) {
    const auto [r, j] = cm.G_pattern[e];
    K(n + long(r), long(j)) = K(long(j), n + long(r)) = k.out[cm.G_out() + e];
  }
  Eigen::VectorXd b(n + m);
  for (long i = 0; i < n; ++i) b[i] = k.out[cm.rhs_out() + size_t(i)];
  for (long r = 0; r < m; ++r) b[n + r] = k.gamma[size_t(r)];
  return K.colPivHouseholderQr().solve(b);
}

void expect_matches_dense_kkt(const std::string& example) {
  auto sys = testing::load_example(example);
  const CompiledModel& cm = *sys.compiled;
  ASSERT_TRUE(dynamics::SparseRangeSpace::suits(cm));
  ASSERT_FALSE(cm.M_diagonal);  // a free body's inertia block
  dynamics::SparseRangeSpace kkt(cm);
  std::vector<double> a(cm.nv), lambda(cm.m);
  for (int state = 0; state < 4; ++state) {
    std::vector<double> q = cm.q0, v = cm.v0;
    for (size_t i = 0; i < cm.nv; ++i) v[i] += 0.3 * state * std::sin(1.0 + double(i + state));
    const KktValues k = kkt_values(*sys.dynamics, 0.1 * state, q, v);
    ASSERT_TRUE(kkt.solve(k.out.data(), k.out.data() + cm.G_out(), k.out.data() + cm.rhs_out(),
                          k.gamma.data(), a.data(), lambda.data()));
    const Eigen::VectorXd x = dense_kkt(cm, k);
    const Eigen::Map<const Eigen::VectorXd> a_sparse(a.data(), long(cm.nv)),
        l_sparse(lambda.data(), long(cm.m));
    const Eigen::VectorXd a_dense = x.head(long(cm.nv)), l_dense = x.tail(long(cm.m));
    EXPECT_LT((a_sparse - a_dense).norm(), 1e-12 * a_dense.norm()) << example << " " << state;
    EXPECT_LT((l_sparse - l_dense).norm(), 1e-12 * l_dense.norm()) << example << " " << state;
    // The same factors for a second right-hand side (the differentiated KKT system's use).
    std::vector<double> a2(cm.nv), l2(cm.m);
    kkt.solve_factored(k.out.data() + cm.G_out(), k.out.data() + cm.rhs_out(), k.gamma.data(),
                       a2.data(), l2.data());
    EXPECT_EQ(a2, a);
    EXPECT_EQ(l2, lambda);
  }
}

TEST(SparseRangeSpace, KiteOnATetherMatchesTheDenseKktSolve) {
  expect_matches_dense_kkt("rigid_kite_ap2.yaml");
}

TEST(SparseRangeSpace, BridledKiteMatchesTheDenseKktSolve) {
  expect_matches_dense_kkt("bridled_kite.yaml");
}

// A block of M that is not positive definite is reported, not solved.
TEST(SparseRangeSpace, RejectsAnIndefiniteMassBlock) {
  const dynamics::Pattern M = {{0, 0}, {0, 1}, {1, 1}, {2, 2}}, G = {{0, 0}, {0, 2}};
  dynamics::SparseRangeSpace kkt(3, 1, M, G);
  const double m_values[] = {1.0, 2.0, 1.0, 1.0};  // [[1, 2], [2, 1]] is indefinite
  const double g[] = {1.0, 1.0}, rhs[] = {0, 0, 0}, gamma[] = {1.0};
  double a[3], lambda[1];
  EXPECT_FALSE(kkt.solve(m_values, g, rhs, gamma, a, lambda));
}

}  // namespace
}  // namespace lagrange
