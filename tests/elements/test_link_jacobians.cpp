// Link Jacobians of the manipulator form (docs/theory.md §4.8): the elbow manipulator's J_v and
// J_ω as in the seed, and D = Σ m J_vᵀJ_v + J_ωᵀ R I Rᵀ J_ω for the seed's arms (symbolically)
// and the UR5 (at random states).

#include <gtest/gtest.h>

#include <random>

#include "support/test_paths.hpp"
#include "lagrange/manipulator.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::sym;

/// Σ over the links of m J_vᵀJ_v + J_ωᵀ R I Rᵀ J_ω.
GiNaC::matrix inertia_from_jacobians(const Model& m, const ManipulatorForm& f) {
  const size_t n = f.eq->nv;
  GiNaC::matrix D(n, n);
  for (const LinkJacobian& J : f.jacobians) {
    const Body* b = nullptr;
    for (const Body& x : m.bodies)
      if (x.name == J.link) b = &x;
    EXPECT_NE(b, nullptr) << J.link;
    if (!b) continue;
    GiNaC::matrix R(3, 3), I(3, 3);
    for (unsigned r = 0; r < 3; ++r)
      for (unsigned c = 0; c < 3; ++c) {
        R(r, c) = b->rotation[r][c];
        I(r, c) = b->inertia[r][c];
      }
    const GiNaC::matrix Iw = R.mul(I).mul(R.transpose());
    D = D.add(J.Jv.transpose().mul(J.Jv).mul_scalar(b->mass))
            .add(J.Jw.transpose().mul(Iw).mul(J.Jw));
  }
  return D;
}

void expect_d_from_jacobians(const std::string& example) {
  const Model m = read_model_file(testing::example_path(example));
  const Equations eq = derive(m);
  const ManipulatorForm f = manipulator_form(eq);
  ASSERT_FALSE(f.jacobians.empty());
  const GiNaC::matrix D = inertia_from_jacobians(m, f);
  for (unsigned i = 0; i < eq.nv; ++i)
    for (unsigned j = 0; j < eq.nv; ++j)
      EXPECT_TRUE(trig_simplify(D(i, j) - f.D(i, j)).is_zero()) << example << " d" << i << j;
}

TEST(LinkJacobians, ElbowIsTheSeeds) {
  const Model m = read_model_file(testing::example_path("elbow_manipulator.yaml"));
  const ManipulatorForm f = manipulator_form(derive(m));
  ASSERT_EQ(f.jacobians.size(), 2u);
  const LinkJacobian& fore = f.jacobians[1];
  EXPECT_EQ(fore.link, "fore");
  const GiNaC::ex q1 = sym(m, "q1"), q2 = sym(m, "q2"), L1 = sym(m, "L1"), Lc2 = sym(m, "Lc2");
  const GiNaC::matrix Jv{{-L1 * sin(q1) - Lc2 * sin(q1 + q2), -Lc2 * sin(q1 + q2)},
                         {L1 * cos(q1) + Lc2 * cos(q1 + q2), Lc2 * cos(q1 + q2)},
                         {0, 0}};
  const GiNaC::matrix Jw{{0, 0}, {0, 0}, {1, 1}};
  for (unsigned r = 0; r < 3; ++r)
    for (unsigned c = 0; c < 2; ++c) {
      EXPECT_TRUE(trig_simplify(fore.Jv(r, c) - Jv(r, c)).is_zero()) << fore.Jv(r, c);
      EXPECT_TRUE(trig_simplify(fore.Jw(r, c) - Jw(r, c)).is_zero()) << fore.Jw(r, c);
    }
}

TEST(LinkJacobians, InertiaMatrixOfTheSeedsArms) {
  expect_d_from_jacobians("elbow_manipulator.yaml");
  expect_d_from_jacobians("two_link_cartesian.yaml");
  expect_d_from_jacobians("five_bar_parallelogram.yaml");
}

TEST(LinkJacobians, InertiaMatrixOfTheUr5AtRandomStates) {
  const Model m = read_model_file(std::string(LAGRANGE_SOURCE_DIR) + "/examples/robots/ur5.urdf");
  const Equations eq = derive(m);
  const ManipulatorForm f = manipulator_form(eq);
  ASSERT_EQ(f.jacobians.size(), 7u);  // base_link (fixed) and six moving links
  const GiNaC::matrix D = inertia_from_jacobians(m, f);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-2, 2);
  GiNaC::exmap at;
  for (size_t i = 0; i < eq.nv; ++i) at[eq.kin.q[i]] = u(rng);
  for (unsigned i = 0; i < eq.nv; ++i)
    for (unsigned j = 0; j < eq.nv; ++j) {
      const double a = GiNaC::ex_to<GiNaC::numeric>(D(i, j).subs(at).evalf()).to_double();
      const double b = GiNaC::ex_to<GiNaC::numeric>(eq.M(i, j).subs(at).evalf()).to_double();
      EXPECT_NEAR(a, b, 1e-13) << i << j;
    }
}

}  // namespace
}  // namespace lagrange
