// docs/theory.md §5.5: trim finds equilibria by Levenberg–Marquardt on the exact Jacobian, keeps
// constrained models on the manifold, and fails with a reason where none can be found.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

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
  try {
    (void)trim(*s.jac, *s.dyn, 0.0, s.q);
    FAIL() << "trim reported an equilibrium where a = -(x^2 + 1)";
  } catch (const AnalysisError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no equilibrium near the start"), std::string::npos) << what;
    EXPECT_NE(what.find("local minimum"), std::string::npos) << what;
    EXPECT_NE(what.find("max |acceleration| = 1"), std::string::npos) << what;  // |a(0)| = 1
  }
}

// a = -(x³ - 3x + 3): |a| has a local minimum 1 at x = 1 (a' = 0 there) and one root, x* =
// -(∛((3 + √5)/2) + ∛((3 - √5)/2)) (Cardano). From x = 2 Levenberg–Marquardt descends ½a² to
// x = 1 and must say that it found no equilibrium there; the overdamped flow ẋ = a runs on
// through x = 1 (a = -1 < 0) to x*, which attracts it (a'(x*) < 0).
TEST(Trim, SpuriousMinimumIsReportedAndTheFlowGoesOnToTheRoot) {
  auto s = analyse_string(R"(
name: spurious minimum
parameters: {m: 1.0}
coordinates:
  x: {initial: 2.0, rate: 0}
kinetic: m/2*der(x)^2
potential: m*(x^4/4 - 3*x^2/2 + 3*x)
)");
  TrimOptions alone;
  alone.max_pseudo_steps = 0;
  try {
    (void)trim(*s.jac, *s.dyn, 0.0, s.q, alone);
    FAIL() << "an equilibrium was reported at the minimum of |a|";
  } catch (const AnalysisError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no equilibrium near the start"), std::string::npos) << what;
    EXPECT_NE(what.find("x = 1"), std::string::npos) << what;  // where it stopped: x = 1.000…
  }
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  EXPECT_TRUE(r.pseudo_transient);
  const double root = -(std::cbrt((3 + std::sqrt(5.0)) / 2) + std::cbrt((3 - std::sqrt(5.0)) / 2));
  EXPECT_NEAR(r.q[0], root, 1e-12);
}

// The small case behind the Panda (docs/theory.md §5.5): a spatial arm whose first joint turns
// about the vertical has no isolated equilibrium anywhere — gravity does not depend on that
// angle, so ∂a/∂q is singular at every state (the former Newton iteration refused at its first
// step). Levenberg–Marquardt moves only where a changes and lands on the family: the yaw as
// given, the shoulder's and the elbow's links vertical, cos q2 = cos(q2 + q3) = 0 (each pitch
// joint carries g (m c) cos of its link's absolute angle); a light forearm (0.05 kg against
// 2 kg) as at the Panda's wrist.
TEST(Trim, ArmTurningAboutTheVerticalLandsOnItsFamilyOfEquilibria) {
  auto s = analyse_string(R"(
name: spatial arm
parameters: {m1: 2.0, m2: 0.05, g: 9.81}
links:
  base:
    joint: {name: q1, type: revolute, axis: [0, 0, 1], initial: 0.3}
    mass: 1.0
    inertia: [0.01, 0.01, 0.02]
  upper:
    parent: base
    joint: {name: q2, type: revolute, axis: [0, 1, 0], origin: {xyz: [0, 0, 0.3]}, initial: 0.4}
    mass: m1
    com: [0.5, 0.02, 0]
    inertia: [0.01, 0.2, 0.2]
  fore:
    parent: upper
    joint: {name: q3, type: revolute, axis: [0, 1, 0], origin: {xyz: [1, 0, 0]}, initial: 0.5}
    mass: m2
    com: [0.4, 0, 0]
    inertia: [0.0005, 0.003, 0.003]
gravity: [0, 0, -g]
)");
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  EXPECT_LE(r.residual, r.tolerance);
  EXPECT_LE(r.tolerance, 1e-10);
  EXPECT_FALSE(r.pseudo_transient);
  EXPECT_NEAR(r.q[0], 0.3, 1e-12);  // nothing moves the yaw
  EXPECT_NEAR(std::cos(r.q[1]), 0.0, 1e-10);
  EXPECT_NEAR(std::cos(r.q[1] + r.q[2]), 0.0, 1e-10);
  EXPECT_NE(r.not_isolated.find("'q1'"), std::string::npos) << r.not_isolated;
}

// Gravity compensation: with the angles held and the joint torques as free inputs, a is affine
// in τ and the first (Newton) step is exact: τ = ∂U/∂q, for point masses on a double pendulum
// (absolute angles from the downward vertical) τ1 = (m1 + m2) g l1 sin θ1, τ2 = m2 g l2 sin θ2.
TEST(Trim, FreeTorquesBalanceGravityInOneIteration) {
  auto s = analyse_string(R"(
name: held double pendulum
parameters: {m1: 1.5, m2: 0.7, l1: 1.2, l2: 0.8, g: 9.81, tau1: 0, tau2: 0}
coordinates:
  th1: {initial: 0.7, rate: 0}
  th2: {initial: -1.1, rate: 0}
points:
  p1: [l1*sin(th1), 0, -l1*cos(th1)]
  p2: p1 + [l2*sin(th2), 0, -l2*cos(th2)]
particles: {p1: m1, p2: m2}
gravity: [0, 0, -g]
generalized_forces: {th1: tau1, th2: tau2}
)",
                          {"tau1", "tau2"});
  TrimOptions options;
  options.free = {false, false};
  options.free_inputs = {true, true};
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q, options);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_LE(r.residual, 1e-12);
  EXPECT_EQ(r.q, s.q);
  ASSERT_EQ(r.inputs.size(), 2u);
  EXPECT_NEAR(r.inputs[0], (1.5 + 0.7) * 9.81 * 1.2 * std::sin(0.7), 1e-12);
  EXPECT_NEAR(r.inputs[1], 0.7 * 9.81 * 0.8 * std::sin(-1.1), 1e-12);
  EXPECT_NEAR(s.dyn->parameters()[5], r.inputs[0], 0.0);  // dyn keeps the torques found
}

// docs/theory.md §5.5, "Tolerance": a spring anchored 10⁸ m from the origin. x is known to
// ε|x| ≈ 1.5e-8 m, so a = -(k/m)(x - X) cannot be computed below about that times k/m; the
// tolerance rises from 1e-10 to the rounding floor 4 ε (k/m)|x| and trim converges there.
TEST(Trim, ToleranceRisesToTheRoundingFloorOfTheAccelerations) {
  auto s = analyse_string(R"(
name: far spring
parameters: {m: 1.0, k: 4.0, X: 1e8}
coordinates:
  x: {initial: 100000010.0, rate: 0}
kinetic: m/2*der(x)^2
potential: k/2*(x - X)^2
)");
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  const double floor = 4 * std::numeric_limits<double>::epsilon() * 4.0 * 1e8;  // ≈ 3.6e-7
  EXPECT_NEAR(r.tolerance, floor, 1e-9 * floor);
  EXPECT_LE(r.residual, r.tolerance);
  EXPECT_NEAR(r.q[0], 1e8, 1e-6);
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
