// The sparse range-space KKT path (block-diagonal M, banded G) against analytic tensions, the
// polar formulation of the same chain, and the KKT equations for a free body on a tether.

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

// A free body with a full inertia tensor (its ω a 3×3 block of M) swinging on a ten-segment
// tether: 33 velocities, so the block-diagonal range-space path solves the KKT system. Its
// accelerations and multipliers satisfy the KKT equations — the DAE residual
// r_v = M a + Gᵀλ − (h + Q), r_λ = G a + c + 2αĊ + α²C, evaluated independently — to rounding.
TEST(SparseKkt, FreeBodyOnATetherSatisfiesTheKktEquations) {
  auto sys = testing::load_string(R"(
gravity: [0, 0, -9.81]
bodies:
  plane:
    mass: 36.8
    inertia: [[25, 0, 0.47], [0, 32, 0], [0.47, 0, 56]]
    frame: free
    initial: {position: [30, 0, 40.3], orientation: {euler: [0.1, pi, 0.2]}, velocity: [0, 5, 0],
              omega: [0.2, -0.1, 0.3]}
    points: {bridle: [0.2, 0.1, 0.3]}
tethers:
  main: {between: [[0, 0, 0], plane.bridle], segments: 10, length: 50, mass_per_length: 0.0046}
)");
  const auto& cm = *sys.compiled;
  ASSERT_FALSE(cm.M_diagonal);
  ASSERT_GE(cm.nv, 24u);
  std::vector<double> q = cm.q0, v = cm.v0, qd(cm.nq), a(cm.nv), lambda(cm.m);
  for (size_t i = 0; i < cm.nv; ++i) v[i] += 0.1 * std::sin(1.0 + static_cast<double>(i));
  sys.dynamics->forward(0.0, q.data(), v.data(), qd.data(), a.data(), lambda.data());
  std::vector<double> r(cm.nq + cm.nv + cm.m);
  sys.dynamics->dae_residual(0.0, q.data(), v.data(), qd.data(), a.data(), lambda.data(), r.data());
  double scale = 0;
  for (double l : lambda) scale = std::max(scale, std::abs(l));
  ASSERT_GT(scale, 1.0);
  for (size_t i = 0; i < r.size(); ++i) EXPECT_NEAR(r[i], 0.0, 1e-10 * scale) << i;
}

}  // namespace
}  // namespace lagrange
