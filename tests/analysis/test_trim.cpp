// docs/theory.md §5.5: trim finds equilibria by Newton's method on the exact Jacobian, keeps
// constrained models on the manifold, and fails with a reason where none can be found.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "analysis/analysed.hpp"

namespace lagrange {
namespace {

using testing::analyse_example;
using testing::analyse_string;

constexpr double kDeg = M_PI / 180.0;

TEST(Trim, PendulumStartedTwentyDegreesAwayLandsAtTheBottom) {
  auto s = analyse_example("pendulum.yaml");
  s.set("theta", 20 * kDeg);
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  EXPECT_NEAR(r.q[0], 0.0, 1e-12);
  EXPECT_LE(r.residual, 1e-10);
  EXPECT_GE(r.iterations, 2);
  EXPECT_LE(r.iterations, 8);
}

TEST(Trim, CartesianPendulumStaysOnTheCircle) {
  auto s = analyse_example("cartesian_pendulum.yaml");
  s.q = {std::sin(20 * kDeg), -std::cos(20 * kDeg)};
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  EXPECT_NEAR(r.q[0], 0.0, 1e-10);
  EXPECT_NEAR(r.q[1], -1.0, 1e-10);
  EXPECT_LE(r.residual, 1e-10);
}

// The double pendulum from (20°, −30°): the hanging equilibrium; fixing θ₁ at 20° leaves no
// equilibrium (θ₁'s own equation cannot balance), which must be said.
TEST(Trim, DoublePendulumAndAFixedCoordinate) {
  auto s = analyse_example("double_pendulum.yaml");
  s.set("theta1", 20 * kDeg);
  s.set("theta2", -30 * kDeg);
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  EXPECT_NEAR(std::remainder(r.q[0], 2 * M_PI), 0.0, 1e-10);  // hanging, up to full turns
  EXPECT_NEAR(std::remainder(r.q[1], 2 * M_PI), 0.0, 1e-10);
  TrimOptions fixed;
  fixed.free = {false, true};
  try {
    (void)trim(*s.jac, *s.dyn, 0.0, s.q, fixed);
    FAIL() << "an equilibrium with theta1 held at 20° was reported";
  } catch (const AnalysisError& e) {
    EXPECT_NE(std::string(e.what()).find("theta1 = 0.349"), std::string::npos) << e.what();
  }
}

// A mass pushed by a constant force with no spring: no equilibrium anywhere; the Jacobian is
// zero, so Newton has no direction: a clear failure, not a wrong answer.
TEST(Trim, ConstantForceWithoutSpringHasNoEquilibrium) {
  auto s = analyse_string(R"(
name: pushed mass
parameters: {m: 2.0, F: 3.0}
coordinates:
  x: {initial: 0.5, rate: 0}
kinetic: m/2*der(x)^2
generalized_forces: {x: F}
)");
  try {
    (void)trim(*s.jac, *s.dyn, 0.0, s.q);
    FAIL() << "trim reported an equilibrium of a constantly pushed mass";
  } catch (const AnalysisError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("singular"), std::string::npos) << what;
    EXPECT_NE(what.find("'x'"), std::string::npos) << what;
    EXPECT_NE(what.find("x = 0.5"), std::string::npos) << what;
  }
}

// a = −(x² + 1) never vanishes but its Jacobian −2x does away from 0: Newton walks towards the
// minimum of |a| at x = 0 and must stop there with a reason.
TEST(Trim, NoRootWithARegularJacobianStopsWithAReason) {
  auto s = analyse_string(R"(
name: no equilibrium
parameters: {m: 1.0}
coordinates:
  x: {initial: 1.0, rate: 0}
kinetic: m/2*der(x)^2
potential: m*(x^3/3 + x)
)");
  EXPECT_THROW((void)trim(*s.jac, *s.dyn, 0.0, s.q), AnalysisError);
}

}  // namespace
}  // namespace lagrange

namespace lagrange {
namespace {

// The lumped chain hung between (0, 0) and (span, 0) from a start that is not its rest shape:
// at a discrete catenary the horizontal tension H is the same in every link and each node's
// weight w steps the vertical one, so the links' slopes tan φ_k = V_k/H fall by the same w/H
// from link to link, and the shape is symmetric about the middle.
TEST(Trim, HangingChainReachesTheDiscreteCatenary) {
  auto s = testing::analyse_example("hanging_chain.yaml");
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  EXPECT_LE(r.residual, 1e-9);
  const CompiledModel& cm = *s.cm;
  const auto at = [&](const std::string& name) {
    const auto it = std::find(cm.coordinate_names.begin(), cm.coordinate_names.end(), name);
    return r.q[static_cast<size_t>(it - cm.coordinate_names.begin())];
  };
  const int N = 20;
  const double span = 8.0;
  std::vector<double> x{0.0}, z{0.0};
  for (int k = 1; k < N; ++k) {
    x.push_back(at("chain.node" + std::to_string(k) + ".x"));
    z.push_back(at("chain.node" + std::to_string(k) + ".z"));
    EXPECT_NEAR(at("chain.node" + std::to_string(k) + ".y"), 0.0, 1e-12);
  }
  x.push_back(span);
  z.push_back(0.0);
  std::vector<double> slope;
  for (int k = 0; k < N; ++k) slope.push_back((z[k + 1] - z[k]) / (x[k + 1] - x[k]));
  const double step = slope[1] - slope[0];
  EXPECT_GT(step, 0.0);  // sagging: slopes rise from −… to +…
  for (int k = 1; k < N; ++k) EXPECT_NEAR(slope[k] - slope[k - 1], step, 1e-9) << "link " << k;
  for (int k = 0; k <= N; ++k) {
    EXPECT_NEAR(x[k] + x[N - k], span, 1e-9);
    EXPECT_NEAR(z[k], z[N - k], 1e-9);
  }
  for (int k = 0; k < N; ++k)  // every link has its length L/N
    EXPECT_NEAR(std::hypot(x[k + 1] - x[k], z[k + 1] - z[k]), 10.0 / N, 1e-12);
}

}  // namespace
}  // namespace lagrange
