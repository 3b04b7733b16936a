// The skeleton of the report's scene (src/io/report_skeleton.cpp) against forward kinematics
// written out by hand for the spatial R-R-P arm of issue 20: joint points, joint axes and the
// prismatic rail over the slider's travel, at every frame.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "lagrange/report.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

// h1 = 0.4, h2 = 0.3, L2 = 0.5, e3 = 0.05: q1 about z at [0, 0, h1], q2 about the upper link's y
// at [0, 0, h2] above it, d3 along the upper link's x from [L2, e3, 0].
const char* kArm = R"(name: rrp arm
parameters: {g: 9.81, m1: 3.0, m2: 2.0, m3: 1.2, h1: 0.4, h2: 0.3, L2: 0.5, c2: 0.25, e3: 0.05}
links:
  base:   {joint: {name: q1, type: revolute, axis: [0, 0, 1], origin: {xyz: [0, 0, h1]}, initial: 0.2, rate: 0.5},
           mass: m1, com: [0, 0, 0.1], inertia: [0.03, 0.03, 0.02]}
  upper:  {parent: base, joint: {name: q2, type: revolute, axis: [0, 1, 0], origin: {xyz: [0, 0, h2]}, initial: -0.4, rate: 0.1},
           mass: m2, com: [c2, 0, 0], inertia: [0.004, 0.045, 0.046]}
  slider: {parent: upper, joint: {name: d3, type: prismatic, axis: [1, 0, 0], origin: {xyz: [L2, e3, 0]}, initial: 0.1, rate: -0.2},
           mass: m3, com: [0.1, 0, 0.02], inertia: [[0.002, 0.0003, 0.0001], [0.0003, 0.011, 0.0002], [0.0001, 0.0002, 0.012]]}
gravity: [0, 0, -g]
simulate: {t_end: 0.6, output_step: 0.01}
)";

Eigen::Vector3d at(const nlohmann::json& flat, size_t offset) {
  return {flat[offset].get<double>(), flat[offset + 1].get<double>(),
          flat[offset + 2].get<double>()};
}

size_t node_index(const nlohmann::json& sk, const std::string& kind, const std::string& name) {
  for (size_t k = 0; k < sk["nodes"].size(); ++k)
    if (sk["nodes"][k]["kind"] == kind && sk["nodes"][k]["name"] == name) return k;
  ADD_FAILURE() << "no " << kind << " node " << name;
  return 0;
}

TEST(ReportSkeleton, JointsAxesAndRailFollowTheArmsForwardKinematics) {
  auto sys = testing::load_string(kArm);
  const Equations eq = derive(*sys.model);
  const Trajectory traj = sys.run(sys.options());
  ASSERT_EQ(traj.status, Trajectory::Status::Complete);
  const auto scene =
      nlohmann::json::parse(report_scene_json(eq, *sys.compiled, traj, sys.dynamics->parameters()));
  const auto& sk = scene["skeleton"];
  const size_t nn = sk["nodes"].size(), na = sk["axes"].size();
  ASSERT_EQ(na, 3u);
  const size_t base = node_index(sk, "base", "world"), shoulder = node_index(sk, "joint", "base"),
               elbow = node_index(sk, "joint", "upper"), slider = node_index(sk, "joint", "slider"),
               anchor = node_index(sk, "anchor", "slider");
  // Bones: world → q1 → q2 → the rail's anchor (where d3 = 0); the rail holds the slider.
  const auto bone = [&](size_t a, size_t b) {
    return std::find(sk["bones"].begin(), sk["bones"].end(), nlohmann::json{a, b}) !=
           sk["bones"].end();
  };
  EXPECT_TRUE(bone(base, shoulder) && bone(shoulder, elbow) && bone(elbow, anchor)) << sk["bones"];
  ASSERT_EQ(sk["rails"].size(), 1u);
  double lo = 0, hi = 0;
  for (size_t r = 0; r < traj.rows(); ++r)
    lo = std::min(lo, traj.at(r, "d3")), hi = std::max(hi, traj.at(r, "d3"));
  ASSERT_GT(hi - lo, 0.05);

  const double tol = 2e-4 * scene["extent"].get<double>();  // the scene's rounding
  const auto& t = scene["t"];
  for (size_t f = 0; f < t.size(); ++f) {
    size_t row = 0;
    while (std::abs(traj.at(row, "t") - t[f].get<double>()) > 1e-12) ++row;
    const double q1 = traj.at(row, "q1"), q2 = traj.at(row, "q2"), d3 = traj.at(row, "d3");
    const Eigen::Matrix3d R1 = Eigen::AngleAxisd(q1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    const Eigen::Matrix3d R2 = R1 * Eigen::AngleAxisd(q2, Eigen::Vector3d::UnitY());
    const Eigen::Vector3d p1(0, 0, 0.4), p2(0, 0, 0.7);
    const auto rail = [&](double d) -> Eigen::Vector3d {
      return p2 + R2 * Eigen::Vector3d(0.5 + d, 0.05, 0);
    };
    const auto& pos = sk["positions"];
    const size_t o = 3 * nn * f;
    EXPECT_LT((at(pos, o + 3 * shoulder) - p1).norm(), tol);
    EXPECT_LT((at(pos, o + 3 * elbow) - p2).norm(), tol);
    EXPECT_LT((at(pos, o + 3 * slider) - rail(d3)).norm(), tol) << "t = " << t[f];
    EXPECT_LT((at(pos, o + 3 * anchor) - rail(0)).norm(), tol);
    const size_t a = sk["rails"][0][0], b = sk["rails"][0][1];
    EXPECT_LT((at(pos, o + 3 * a) - rail(lo)).norm(), tol);
    EXPECT_LT((at(pos, o + 3 * b) - rail(hi)).norm(), tol);
    // Axes in the world: z, the upper link's y after q1, the slider's x after q1 and q2.
    const auto& dir = sk["directions"];
    EXPECT_LT((at(dir, 3 * na * f) - Eigen::Vector3d::UnitZ()).norm(), 1e-4);
    EXPECT_LT((at(dir, 3 * na * f + 3) - R1 * Eigen::Vector3d::UnitY()).norm(), 1e-4);
    EXPECT_LT((at(dir, 3 * na * f + 6) - R2 * Eigen::Vector3d::UnitX()).norm(), 1e-4);
  }
}

TEST(ReportSkeleton, AModelWithoutAJointTreeHasNone) {
  auto sys = testing::load_example("double_pendulum.yaml");
  const Equations eq = derive(*sys.model);
  SimulationOptions so = sys.options();
  so.t_end = 0.2;
  const Trajectory traj = sys.run(so);
  const auto scene =
      nlohmann::json::parse(report_scene_json(eq, *sys.compiled, traj, sys.dynamics->parameters()));
  EXPECT_FALSE(scene.contains("skeleton"));
}

}  // namespace
}  // namespace lagrange
