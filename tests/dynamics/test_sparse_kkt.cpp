// The sparse range-space KKT path (diagonal M, banded G) against analytic tensions and the
// polar formulation of the same chain.

#include <gtest/gtest.h>

#include <cmath>

#include "n_link_pendulum.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

using bench::cartesian_chain_yaml;  // l = 0.5, unit masses, g = 9.81

TEST(SparseKkt, HangingChainTensionsAreTheWeightBelow) {
  const int N = 15;  // 30 coordinates: above the sparse threshold
  auto sys = testing::load_string(cartesian_chain_yaml(N, 0.0));
  const auto& cm = *sys.compiled;
  ASSERT_TRUE(cm.M_diagonal);
  std::vector<double> qd(cm.nq), a(cm.nv), lambda(cm.m);
  const std::vector<double> v(cm.nv, 0.0);
  sys.dynamics->forward(0.0, cm.q0.data(), v.data(), qd.data(), a.data(), lambda.data());
  for (size_t i = 0; i < cm.nv; ++i) EXPECT_NEAR(a[i], 0.0, 1e-10) << i;
  // C = (|d|² − l²)/2 ⇒ rod force λ d, tension λ l = (N − i + 1) m g.
  for (int i = 1; i <= N; ++i)
    EXPECT_NEAR(lambda[static_cast<size_t>(i - 1)] * 0.5, (N - i + 1) * 9.81, 1e-9) << i;
}

TEST(SparseKkt, SwingingChainConservesEnergyAndConstraints) {
  auto sys = testing::load_string(cartesian_chain_yaml(14, 0.7));
  SimulationOptions so = sys.options();
  so.t_end = 2;
  so.output_step = 0.01;
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double e0 = tr.at(0, "energy");
  for (size_t r = 0; r < tr.rows(); ++r) {
    EXPECT_NEAR(tr.at(r, "energy"), e0, 1e-6 * std::abs(e0)) << tr.at(r, "t");
    EXPECT_LT(tr.at(r, "constraint_residual"), 1e-9);
  }
}

}  // namespace
}  // namespace lagrange
