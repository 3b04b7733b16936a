// Rigid bodies read from model files (docs/theory.md §4.4): the bundled body examples against each
// other and against the physics they illustrate, and torques and body-point elements from YAML.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::load_example;
using testing::load_string;
using testing::omega_at;
using testing::rotation_at;
using testing::tight;

// compound_pendulum.yaml (SO(3) + pivot constraint) and compound_pendulum_planar.yaml (one
// angle, posed by rot_z) describe the same bar: same angle and rate over 10 s.
TEST(BodyExamples, CompoundPendulumFilesAgree) {
  auto so3 = load_example("compound_pendulum.yaml");
  auto planar = load_example("compound_pendulum_planar.yaml");
  const Trajectory a = so3.run(tight(so3, 10, 0.01));
  const Trajectory b = planar.run(tight(planar, 10, 0.01));
  ASSERT_EQ(a.status, Trajectory::Status::Complete) << a.message;
  ASSERT_EQ(b.status, Trajectory::Status::Complete) << b.message;
  ASSERT_EQ(a.rows(), b.rows());
  double worst = 0;
  for (size_t r = 0; r < a.rows(); ++r) {
    worst =
        std::max({worst, std::abs(std::remainder(a.at(r, "angle") - b.at(r, "theta"), 2 * M_PI)),
                  std::abs(a.at(r, "bar.wz") - b.at(r, "theta_dot"))});
    ASSERT_LT(b.at(r, "pivot_drift"), 1e-12);
  }
  RecordProperty("so3_vs_planar_files", fmt::format("{:.3e}", worst));
  EXPECT_LT(worst, 1e-7);
  // The bar swings through the bottom: θ changes sign.
  double lo = 0, hi = 0;
  for (size_t r = 0; r < b.rows(); ++r) {
    lo = std::min(lo, b.at(r, "theta"));
    hi = std::max(hi, b.at(r, "theta"));
  }
  EXPECT_LT(lo, -0.9);
  EXPECT_GT(hi, 0.9);
}

// tumbling_brick.yaml: the intermediate-axis spin flips (ω_y changes sign and reaches −ω₀)
// while T and the world angular momentum R J ω stay constant.
TEST(BodyExamples, TumblingBrickFlips) {
  auto sys = load_example("tumbling_brick.yaml");
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double m = 1, a = 0.3, b = 0.2, c = 0.1;
  const Eigen::Vector3d I(m * (b * b + c * c) / 12, m * (a * a + c * c) / 12,
                          m * (a * a + b * b) / 12);
  auto momentum = [&](size_t r) {
    const Eigen::Vector3d w(tr.at(r, "brick.wx"), tr.at(r, "brick.wy"), tr.at(r, "brick.wz"));
    return Eigen::Vector3d(rotation_at(tr, r, "brick") * I.asDiagonal() * w);
  };
  int flips = 0;
  double lowest = 1, worst_L = 0;
  for (size_t r = 1; r < tr.rows(); ++r) {
    if ((tr.at(r, "brick.wy") > 0) != (tr.at(r - 1, "brick.wy") > 0)) ++flips;
    lowest = std::min(lowest, tr.at(r, "brick.wy") / 5.0);
    worst_L = std::max(worst_L, (momentum(r) - momentum(0)).norm() / momentum(0).norm());
  }
  RecordProperty("flips", flips);
  RecordProperty("momentum_relative_drift", fmt::format("{:.3e}", worst_L));
  EXPECT_GE(flips, 2);
  EXPECT_LT(lowest, -0.9);
  EXPECT_LT(worst_L, 1e-8);
  // The output spin_axis_y is the body y axis in the world frame: it turns over too.
  double min_y = 1;
  for (size_t r = 0; r < tr.rows(); ++r) min_y = std::min(min_y, tr.at(r, "spin_axis_y.y"));
  EXPECT_LT(min_y, -0.9);
}

// heavy_top.yaml precesses at m g d / (I₃ ω₃) within 1 % (fast top), pivot held by C(r, R).
TEST(BodyExamples, HeavyTopPrecesses) {
  auto sys = load_example("heavy_top.yaml");
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  double total = 0;
  auto azimuth = [&](size_t r) { return std::atan2(tr.at(r, "axis.x"), -tr.at(r, "axis.y")); };
  for (size_t r = 1; r < tr.rows(); ++r)
    total += std::remainder(azimuth(r) - azimuth(r - 1), 2 * M_PI);
  const double rate = total / tr.at(tr.rows() - 1, "t");
  const double predicted = 1.0 * 9.81 * 0.1 / (0.01 * 200);
  RecordProperty("precession_rate", fmt::format("{:.4e}", rate));
  EXPECT_NEAR(rate, predicted, 0.01 * predicted);
}

// A body-frame torque τ about z spins a free body up at ω̇_z = τ/I_zz whatever its attitude;
// the same torque in the world frame, on a body turned 90° about x (R ŷ = ẑ), acts about
// body +y: ω̇_y = τ/I_yy.
TEST(BodyExamples, TorquesInBodyAndWorldFrames) {
  const std::string base = R"(bodies:
  b:
    mass: 2
    inertia: [2, 3, 4]
    frame: free
    initial: {orientation: {axis_angle: {axis: [1, 0, 0], angle: pi/2}}}
torques:
  - {body: b, torque: [0, 0, 0.8], frame: )";
  auto body_frame = load_string(base + "body}\nsimulate: {t_end: 2, output_step: 0.5}\n");
  const Trajectory a = body_frame.run(tight(body_frame, 2, 0.5));
  ASSERT_EQ(a.status, Trajectory::Status::Complete) << a.message;
  EXPECT_NEAR(a.at(a.rows() - 1, "b.wz"), 0.8 / 4 * 2, 1e-10);
  EXPECT_NEAR(a.at(a.rows() - 1, "b.wx"), 0, 1e-10);
  auto world_frame = load_string(base + "world}\nsimulate: {t_end: 2, output_step: 0.5}\n");
  const Trajectory w = world_frame.run(tight(world_frame, 2, 0.5));
  ASSERT_EQ(w.status, Trajectory::Status::Complete) << w.message;
  EXPECT_NEAR(w.at(w.rows() - 1, "b.wy"), 0.8 / 3 * 2, 1e-10);
  EXPECT_NEAR(w.at(w.rows() - 1, "b.wz"), 0, 1e-10);
}

// A free body hung from a spring at a body point, with gravity: energy is conserved and the
// body point's velocity output matches the finite difference of its position.
TEST(BodyExamples, SpringAtABodyPointConservesEnergy) {
  auto sys = load_string(R"(parameters: {k: 50, g: 9.81}
bodies:
  box:
    mass: 1
    shape: {box: [0.2, 0.1, 0.4]}
    frame: free
    initial: {position: [0.1, 0, -0.5], omega: [1, 0.5, 0], velocity: [0, 0.3, 0]}
    points: {hook: [0.05, 0.02, 0.2]}
points:
  ceiling: [0, 0, 0]
springs:
  - {between: [ceiling, box.hook], k: k, l0: 0.3}
gravity: [0, 0, -g]
outputs:
  hook: box.hook
  hook_v: vel(box.hook)
)");
  const Trajectory tr = sys.run(tight(sys, 5, 0.001));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double e0 = tr.at(0, "energy");
  double worst_e = 0, worst_v = 0;
  for (size_t r = 1; r + 1 < tr.rows(); ++r) {
    worst_e = std::max(worst_e, std::abs(tr.at(r, "energy") - e0));
    const double fd = (tr.at(r + 1, "hook.z") - tr.at(r - 1, "hook.z")) / 0.002;
    worst_v = std::max(worst_v, std::abs(fd - tr.at(r, "hook_v.z")));
  }
  RecordProperty("energy_drift", fmt::format("{:.3e}", worst_e));
  EXPECT_LT(worst_e, 1e-8 * std::max(1.0, std::abs(e0)));
  EXPECT_LT(worst_v, 1e-3);
}

}  // namespace
}  // namespace lagrange
