// The links element composes each body's angular velocity along the chain,
// ω_child = R_relᵀ ω_parent + k q̇ (docs/theory.md §4.8), instead of leaving the core to derive
// U(RᵀṘ) from the product of rotations. Both must be the same function of (q, q̇): symbolically
// for the seed's planar arms, at random states for the URDF arms.

#include <gtest/gtest.h>

#include <random>

#include "support/harness.hpp"
#include "symbolic/mechanical_terms.hpp"

namespace lagrange {
namespace {

/// Each composed ω next to the one the core derives from R, for every body that has one.
struct Pair {
  std::string body;
  Vec3 composed, derived;
};

std::vector<Pair> angular_velocities(const Model& model) {
  const Kinematics kin = kinematics(model);
  std::vector<Pair> out;
  for (const Body& b : model.bodies) {
    if (!b.angular_velocity) continue;
    Body plain = b;
    plain.angular_velocity.reset();
    out.push_back({b.name, *b.angular_velocity, symbolic::body_angular_velocity(kin, plain)});
  }
  return out;
}

class PlanarArm : public ::testing::TestWithParam<std::string> {};

TEST_P(PlanarArm, ComposedEqualsDerivedSymbolically) {
  const Model model = read_model_file(testing::example_path(GetParam()));
  const auto pairs = angular_velocities(model);
  ASSERT_FALSE(pairs.empty());
  for (const Pair& p : pairs)
    for (size_t i = 0; i < 3; ++i)
      EXPECT_TRUE(testing::same(p.composed[i], p.derived[i]))
          << p.body << " ω[" << i << "]: " << p.composed[i] << " vs " << p.derived[i];
}

INSTANTIATE_TEST_SUITE_P(Seed001, PlanarArm,
                         ::testing::Values("elbow_manipulator.yaml", "two_link_cartesian.yaml",
                                           "planar_arm_pd.yaml"),
                         [](const auto& info) { return testing::model_label(info.param); });

class UrdfArm : public ::testing::TestWithParam<std::string> {};

TEST_P(UrdfArm, ComposedEqualsDerivedAtRandomStates) {
  const Model model = read_model_file(testing::example_path(GetParam()));
  const auto pairs = angular_velocities(model);
  ASSERT_GE(pairs.size(), 6u);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int k = 0; k < 5; ++k) {
    GiNaC::exmap at;
    for (const auto& p : model.parameters) at[p.sym] = p.value;
    for (const auto& c : model.coordinates) {
      at[c.q] = u(rng);
      at[c.v] = u(rng);
    }
    for (const Pair& p : pairs)
      for (size_t i = 0; i < 3; ++i) {
        const double a = GiNaC::ex_to<GiNaC::numeric>(p.composed[i].subs(at).evalf()).to_double();
        const double b = GiNaC::ex_to<GiNaC::numeric>(p.derived[i].subs(at).evalf()).to_double();
        EXPECT_NEAR(a, b, 1e-12 * (1 + std::abs(b))) << p.body << " ω[" << i << "], state " << k;
      }
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, UrdfArm, ::testing::Values("robots/ur5.urdf", "robots/panda.urdf"),
                         [](const auto& info) { return testing::model_label(info.param); });

}  // namespace
}  // namespace lagrange
