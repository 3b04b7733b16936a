// Constrained systems (docs/theory.md §4.3): multiplier oracles from seed 000, agreement between
// formulations, drift with and without stabilisation, projection of inconsistent states.

#include <gtest/gtest.h>

#include <cmath>

#include "lagrange/error.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::load_example;
using testing::load_string;

double max_over(const Trajectory& tr, const std::string& col) {
  double w = 0;
  for (size_t r = 0; r < tr.rows(); ++r) w = std::max(w, std::abs(tr.at(r, col)));
  return w;
}

TEST(Constrained, PolarPendulumTensionOracle) {
  auto sys = load_example("constrained_pendulum.yaml");
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double m = 1.0, g = 9.81;
  for (size_t r = 0; r < tr.rows(); r += 7) {
    const double l = tr.at(r, "l"), th = tr.at(r, "theta"), thd = tr.at(r, "theta_dot");
    const double expected = m * l * thd * thd + m * g * std::cos(th);
    EXPECT_NEAR(tr.at(r, "rod"), expected, 1e-8 * std::abs(expected)) << "t = " << tr.at(r, "t");
  }
  EXPECT_LT(max_over(tr, "constraint_residual"), 1e-9);
}

TEST(Constrained, CartesianPendulumTensionOracle) {
  auto sys = load_example("cartesian_pendulum.yaml");
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double m = 1.0, g = 9.81, l = 1.0;
  for (size_t r = 0; r < tr.rows(); r += 7) {
    const double xd = tr.at(r, "x_dot"), yd = tr.at(r, "y_dot"), y = tr.at(r, "y");
    const double expected = m * (xd * xd + yd * yd - g * y) / (l * l);
    EXPECT_NEAR(tr.at(r, "rod"), expected, 1e-8 * std::abs(expected)) << "t = " << tr.at(r, "t");
  }
}

TEST(Constrained, PolarAndCartesianPendulumAgree) {
  auto polar = load_example("pendulum.yaml");
  auto cart = load_example("cartesian_pendulum.yaml");
  const SimulationOptions so = testing::tight(polar, 10, 0.01);
  std::vector<double> q0{1.0}, v0{0.0};
  const Trajectory a = simulate(*polar.dynamics, so, q0, v0);
  const Trajectory b = simulate(*cart.dynamics, so, {std::sin(1.0), -std::cos(1.0)}, {0.0, 0.0});
  ASSERT_EQ(a.rows(), b.rows());
  double worst = 0;
  for (size_t r = 0; r < a.rows(); ++r)
    worst = std::max(worst, std::abs(a.at(r, "theta") - std::atan2(b.at(r, "x"), -b.at(r, "y"))));
  EXPECT_LT(worst, 1e-7);
}

TEST(Constrained, DoublePendulumPolarAndCartesianAgree) {
  auto polar = load_example("double_pendulum.yaml");
  auto cart = load_example("double_pendulum_cartesian.yaml");
  const SimulationOptions so = testing::tight(polar, 10, polar.model->simulate.output_step);
  const Trajectory a = simulate(*polar.dynamics, so, {0.5, 1.0}, {0.0, 0.0});
  const Trajectory b = cart.run(so);
  ASSERT_EQ(b.status, Trajectory::Status::Complete) << b.message;
  double worst = 0;
  for (size_t r = 0; r < a.rows(); ++r) {
    worst = std::max(worst, std::abs(a.at(r, "theta1") - b.at(r, "theta1")));
    worst = std::max(worst, std::abs(a.at(r, "theta2") - b.at(r, "theta2")));
  }
  EXPECT_LT(worst, 1e-7);
}

TEST(Constrained, DriftWithoutStabilisationAndWithDefaults) {
  auto sys = load_example("cartesian_pendulum.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 100;
  so.output_step = 0.1;
  so.integrator.rtol = 1e-6;
  so.integrator.atol = 1e-8;
  so.project = false;
  sys.dynamics->set_baumgarte(0.0);
  const Trajectory raw = sys.run(so);
  ASSERT_EQ(raw.status, Trajectory::Status::Complete) << raw.message;
  const double drift = raw.at(raw.rows() - 1, "constraint_residual");
  EXPECT_GT(drift, 1e-6) << "the unstabilised index-1 form should drift";
  // The defaults (the run's Baumgarte α + projection after drifting steps and at samples).
  sys.dynamics->set_baumgarte(baumgarte_rate(sys.model->stabilization, so.integrator.method));
  so.project = true;
  const Trajectory stab = sys.run(so);
  EXPECT_LT(max_over(stab, "constraint_residual"), 1e-9);
  EXPECT_LT(max_over(stab, "constraint_rate_residual"), 1e-9);
}

TEST(Constrained, BaumgarteErrorDecaysAtRateAlpha) {
  // Start off the manifold (C ≠ 0) without projection: C̈ + 2αĊ + α²C = 0 gives
  // C(t) = C0 (1 + α t) e^{−α t}; fit log(C / (1 + α t)) against t.
  auto sys = load_example("cartesian_pendulum.yaml");
  const double alpha = 5.0;
  sys.dynamics->set_baumgarte(alpha);
  SimulationOptions so = sys.options();
  so.t_end = 2.0;
  so.output_step = 0.05;
  so.project = false;
  so.project_initial = false;
  so.projection_tol = 1.0;  // accept the deliberately inconsistent start
  so.integrator.rtol = 1e-12;
  so.integrator.atol = 1e-14;
  const Trajectory tr = simulate(*sys.dynamics, so, {0.0, -1.01}, {0.0, 0.0});
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int count = 0;
  for (size_t r = 2; r < tr.rows(); ++r) {
    const double t = tr.at(r, "t"), C = tr.at(r, "constraint_residual");
    if (C < 1e-10) break;
    const double y = std::log(C / (1 + alpha * t));
    sx += t, sy += y, sxx += t * t, sxy += t * y, ++count;
  }
  ASSERT_GT(count, 10);
  const double slope = (count * sxy - sx * sy) / (count * sxx - sx * sx);
  EXPECT_NEAR(slope, -alpha, 0.01 * alpha);
}

TEST(Constrained, IdaAgreesWithOdePath) {
  auto sys = load_example("cartesian_pendulum.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 5;
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  const Trajectory ode = sys.run(so);
  so.integrator.method = "ida";
  const Trajectory dae = sys.run(so);
  ASSERT_EQ(dae.status, Trajectory::Status::Complete) << dae.message;
  ASSERT_EQ(ode.rows(), dae.rows());
  double worst = 0;
  for (size_t r = 0; r < ode.rows(); ++r)
    for (const char* c : {"x", "y", "x_dot", "y_dot"})
      worst = std::max(worst, std::abs(ode.at(r, c) - dae.at(r, c)));
  EXPECT_LT(worst, 1e-6);
}

TEST(Constrained, InconsistentInitialStateIsProjectedAndReported) {
  auto sys = load_example("cartesian_pendulum.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 0.1;
  const Trajectory tr = simulate(*sys.dynamics, so, {0.9, -0.6}, {0.3, 0.0});
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  ASSERT_EQ(tr.notes.size(), 1u);
  EXPECT_NE(tr.notes[0].find("inconsistent"), std::string::npos) << tr.notes[0];
  EXPECT_NE(tr.notes[0].find("x: 0.9 ->"), std::string::npos) << tr.notes[0];
  EXPECT_LT(tr.at(0, "constraint_residual"), 1e-12);
  EXPECT_LT(tr.at(0, "constraint_rate_residual"), 1e-12);
  // The least-squares change of (x, y) onto the circle keeps the direction.
  EXPECT_NEAR(tr.at(0, "x") / tr.at(0, "y"), 0.9 / -0.6, 1e-9);
}

TEST(Constrained, FixedCoordinatesAreKeptByProjection) {
  auto sys = load_example("five_bar.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 2;
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  EXPECT_DOUBLE_EQ(tr.at(0, "th1"), 1.8);
  EXPECT_DOUBLE_EQ(tr.at(0, "th3"), 1.2);
  EXPECT_DOUBLE_EQ(tr.at(0, "th1_dot"), 0.5);
  EXPECT_LT(max_over(tr, "constraint_residual"), 1e-9);
  // Closed kinematic loop without friction conserves energy.
  EXPECT_NEAR(tr.at(tr.rows() - 1, "energy"), tr.at(0, "energy"),
              1e-6 * std::abs(tr.at(0, "energy")));
}

TEST(Constrained, RedundantConstraintsAreNamed) {
  auto sys = load_string(R"(
name: redundant
parameters: {m: 1.0, g: 9.81, l: 1.0}
coordinates:
  x: {initial: 0.6}
  y: {initial: -0.8}
points: {bob: [x, y, 0]}
particles: {bob: m}
gravity: [0, -g, 0]
constraints:
  rod: (x^2 + y^2 - l^2)/2
  rod_again: x^2 + y^2 - l^2
)");
  std::vector<double> qd(2), a(2), lambda(2);
  const std::vector<double> q{0.6, -0.8}, v{0.0, 0.0};
  try {
    sys.dynamics->forward(0.25, q.data(), v.data(), qd.data(), a.data(), lambda.data());
    FAIL() << "expected a SimulationError";
  } catch (const SimulationError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("t = 0.25"), std::string::npos) << msg;
    EXPECT_NE(msg.find("redundant or singular"), std::string::npos) << msg;
    EXPECT_TRUE(msg.find("'rod'") != std::string::npos ||
                msg.find("'rod_again'") != std::string::npos)
        << msg;
  }
}

TEST(Constrained, CraneFollowsPrescribedRope) {
  auto sys = load_example("crane.yaml");
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  EXPECT_LT(max_over(tr, "constraint_residual"), 1e-9);
  // Rope length at t is L0 − dL (1 − cos t)/2 and the load hangs on it.
  const size_t last = tr.rows() - 1;
  const double t = tr.at(last, "t");
  const double xc = 1.0 * (1 - std::cos(t)), L = 2.0 - 0.5 * (1 - std::cos(t)) / 2;
  EXPECT_NEAR(std::hypot(tr.at(last, "x") - xc, tr.at(last, "y")), L, 1e-9);
  EXPECT_GT(tr.at(last, "rope"), 0.0);  // a rope only pulls
}

}  // namespace
}  // namespace lagrange

namespace lagrange {
namespace {

TEST(Constrained, SingularMassMatrixSolvedThroughFullKkt) {
  // The five-bar with the coupler-pin mass on one coupler only: th4 has no inertia of its
  // own (M singular), yet the constrained system is regular. Same motion as the split mass.
  auto split = testing::load_example("five_bar.yaml");
  Model one = read_model_file(testing::example_path("five_bar.yaml"));
  one.particles.pop_back();
  one.particles.back().mass = one.particles.back().mass * 2;
  auto single = testing::load_model(std::make_unique<Model>(one));
  SimulationOptions so = split.options();
  so.t_end = 1;
  const Trajectory a = split.run(so), b = single.run(so);
  ASSERT_EQ(b.status, Trajectory::Status::Complete) << b.message;
  for (size_t r = 0; r < a.rows(); r += 10)
    for (const char* c : {"th1", "th2", "th3", "th4", "th2_dot", "th4_dot"})
      EXPECT_NEAR(a.at(r, c), b.at(r, c), 1e-7) << c << " at t = " << a.at(r, "t");
}

}  // namespace
}  // namespace lagrange
