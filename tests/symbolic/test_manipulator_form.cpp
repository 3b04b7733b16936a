// The manipulator form (src/symbolic/manipulator_form.cpp, docs/theory.md §4.8) against the seed's
// worked examples (seed 001), the skew symmetry of Ḋ − 2C, and the generic Euler–Lagrange path.

#include <gtest/gtest.h>

#include "lagrange/manipulator.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::example_path;
using testing::sym;

bool trig_same(const GiNaC::ex& a, const GiNaC::ex& b) {
  return trig_simplify(a - b).is_zero();
}

GiNaC::ex christoffel(const ManipulatorForm& f, size_t i, size_t j, size_t k) {
  for (const Christoffel& c : f.christoffel)
    if (c.i == i - 1 && c.j == j - 1 && c.k == k - 1) return c.value;
  return 0;
}

// Seed 001, Example 5: the two-link elbow manipulator.
TEST(ManipulatorForm, ElbowManipulatorMatchesTheSeed) {
  const Model m = read_model_file(example_path("elbow_manipulator.yaml"));
  const Equations eq = derive(m);
  const ManipulatorForm f = manipulator_form(eq);
  const auto m1 = sym(m, "m1"), m2 = sym(m, "m2"), L1 = sym(m, "L1"), Lc1 = sym(m, "Lc1"),
             Lc2 = sym(m, "Lc2"), I1 = sym(m, "I1"), I2 = sym(m, "I2"), q2 = sym(m, "q2");
  EXPECT_TRUE(trig_same(
      f.D(0, 0), m1 * Lc1 * Lc1 + m2 * (L1 * L1 + Lc2 * Lc2 + 2 * L1 * Lc2 * cos(q2)) + I1 + I2))
      << f.D(0, 0);
  EXPECT_TRUE(trig_same(f.D(0, 1), m2 * (Lc2 * Lc2 + L1 * Lc2 * cos(q2)) + I2)) << f.D(0, 1);
  EXPECT_TRUE(trig_same(f.D(1, 0), f.D(0, 1)));
  EXPECT_TRUE(trig_same(f.D(1, 1), m2 * Lc2 * Lc2 + I2)) << f.D(1, 1);
  const GiNaC::ex h = -m2 * L1 * Lc2 * sin(q2);
  EXPECT_TRUE(trig_same(christoffel(f, 1, 2, 1), h)) << christoffel(f, 1, 2, 1);
  EXPECT_TRUE(trig_same(christoffel(f, 2, 1, 1), h));
  EXPECT_TRUE(trig_same(christoffel(f, 2, 2, 1), h));
  EXPECT_TRUE(trig_same(christoffel(f, 1, 1, 2), -h));
  EXPECT_EQ(f.christoffel.size(), 4u);  // c111 = c122 = c212 = c222 = 0
  const auto g = sym(m, "g"), q1 = sym(m, "q1");
  EXPECT_TRUE(trig_same(f.g[1], m2 * g * Lc2 * cos(q1 + q2))) << f.g[1];
}

// Seed 001: the two-link Cartesian arm's K and P.
TEST(ManipulatorForm, TwoLinkCartesianArmEnergies) {
  const Model m = read_model_file(example_path("two_link_cartesian.yaml"));
  const Equations eq = derive(m);
  const auto m1 = sym(m, "m1"), m2 = sym(m, "m2"), l = sym(m, "l"), g = sym(m, "g");
  const auto q2 = sym(m, "q2"), v1 = sym(m, "q1_dot"), v2 = sym(m, "q2_dot");
  const GiNaC::ex K =
      m1 * v1 * v1 / 2 + m2 * (v1 * v1 + l * l * v2 * v2 - 2 * l * v1 * v2 * sin(q2)) / 2;
  EXPECT_TRUE(trig_same(eq.T, K)) << eq.T;
  EXPECT_TRUE(trig_same(eq.U, m2 * g * l * sin(q2))) << eq.U;
  const ManipulatorForm f = manipulator_form(eq);
  EXPECT_TRUE(trig_same(f.D(0, 1), -m2 * l * sin(q2))) << f.D(0, 1);
}

class SkewSymmetry : public ::testing::TestWithParam<const char*> {};

// Ḋ − 2C is skew-symmetric, and D q̈ = τ − C q̇ − g gives the generic path's accelerations.
TEST_P(SkewSymmetry, DDotMinusTwoCIsSkewAndAccelerationsAgree) {
  const Model m = read_model_file(example_path(GetParam()));
  const Equations eq = derive(m);
  const ManipulatorForm f = manipulator_form(eq);
  const GiNaC::matrix N = d_dot_minus_2c(f);
  const size_t n = eq.nv;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j)
      EXPECT_TRUE(trig_simplify(N(i, j) + N(j, i)).is_zero()) << i << j << ": " << N(i, j);
  GiNaC::matrix rhs(n, 1);
  for (size_t k = 0; k < n; ++k) {
    GiNaC::ex r = f.tau[k] - f.g[k];
    for (size_t j = 0; j < n; ++j) r -= f.C(k, j) * eq.kin.v[j];
    rhs(k, 0) = r;
  }
  const GiNaC::matrix a = f.D.inverse().mul(rhs);
  const auto generic = solve_accelerations(eq);
  for (size_t k = 0; k < n; ++k) EXPECT_TRUE(trig_same(a(k, 0), generic[k])) << k;
}

INSTANTIATE_TEST_SUITE_P(Examples, SkewSymmetry,
                         ::testing::Values("elbow_manipulator.yaml", "two_link_cartesian.yaml",
                                           "planar_arm_pd.yaml", "double_pendulum.yaml"),
                         [](const auto& info) {
                           std::string s = info.param;
                           return s.substr(0, s.find('.'));
                         });

TEST(ManipulatorForm, RefusesConstrainedModelsFreeBodiesAndMovingBases) {
  const Model five_bar = read_model_file(example_path("five_bar.yaml"));
  EXPECT_THROW(manipulator_form(derive(five_bar)), std::invalid_argument);
  const Model top = read_model_file(example_path("heavy_top.yaml"));
  EXPECT_THROW(manipulator_form(derive(top)), std::invalid_argument);
  // A pendulum whose support moves with t: h has a term that is not −C q̇ − g.
  const Model moving = read_model_string(R"(parameters: {l: 1, g: 9.81}
coordinates: {th: {initial: 0.1}}
points: {bob: [sin(t) + l*sin(th), -l*cos(th), 0]}
particles: {bob: 1}
gravity: [0, -g, 0]
)",
                                         "<moving>");
  try {
    manipulator_form(derive(moving));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("moving base"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lagrange
