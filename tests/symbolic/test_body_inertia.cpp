// Inertia of shapes and the parallel-axis theorem against hand values (docs/theory.md §4.8), the
// physical-inertia check naming the body, and initial orientations (docs/theory.md §4.4).

#include <gtest/gtest.h>

#include <cmath>

#include "lagrange/equations.hpp"
#include "lagrange/error.hpp"
#include "lagrange/rigid_body.hpp"

namespace lagrange {
namespace {

double num(const GiNaC::ex& e) {
  return GiNaC::ex_to<GiNaC::numeric>(e.evalf()).to_double();
}

TEST(BodyInertia, ShapesMatchHandValues) {
  // Box 2 kg, 0.3 × 0.4 × 1.2: I_xx = 2(0.16 + 1.44)/12, I_yy = 2(0.09 + 1.44)/12, I_zz = 2(0.09 +
  // 0.16)/12.
  const Mat3 box = box_inertia(2, 0.3, 0.4, 1.2);
  EXPECT_NEAR(num(box[0][0]), 2 * 1.60 / 12, 1e-15);
  EXPECT_NEAR(num(box[1][1]), 2 * 1.53 / 12, 1e-15);
  EXPECT_NEAR(num(box[2][2]), 2 * 0.25 / 12, 1e-15);
  EXPECT_EQ(num(box[0][1]), 0.0);
  // Cylinder 3 kg, r = 0.1, h = 0.6 along z: I_zz = 3·0.01/2, I_xx = 3(0.03 + 0.36)/12.
  const Mat3 cyl = cylinder_inertia(3, 0.1, 0.6);
  EXPECT_NEAR(num(cyl[2][2]), 0.015, 1e-15);
  EXPECT_NEAR(num(cyl[0][0]), 3 * 0.39 / 12, 1e-15);
  EXPECT_NEAR(num(cyl[1][1]), 3 * 0.39 / 12, 1e-15);
  // Sphere 5 kg, r = 0.2: 2/5 · 5 · 0.04 = 0.08.
  const Mat3 sph = sphere_inertia(5, 0.2);
  for (size_t i = 0; i < 3; ++i) EXPECT_NEAR(num(sph[i][i]), 0.08, 1e-15);
}

TEST(BodyInertia, ParallelAxisTheorem) {
  // Rod of mass m, length l about its end: m l²/12 + m (l/2)² = m l²/3.
  const GiNaC::symbol m("m"), l("l");
  const Mat3 rod = box_inertia(m, 0, l, 0);
  const Mat3 end = parallel_axis(rod, m, {0, l / 2, 0});
  EXPECT_TRUE((end[0][0] - m * l * l / 3).expand().is_zero());
  EXPECT_TRUE((end[2][2] - m * l * l / 3).expand().is_zero());
  EXPECT_TRUE(end[1][1].expand().is_zero());
  // Off-diagonal products of inertia for an offset d = (1, 2, 0), m = 2: −m dₓ d_y = −4.
  const Mat3 off = parallel_axis(principal_inertia(1, 1, 1), 2, {1, 2, 0});
  EXPECT_NEAR(num(off[0][1]), -4.0, 1e-15);
  EXPECT_NEAR(num(off[0][0]), 1 + 2 * 4.0, 1e-15);
  EXPECT_NEAR(num(off[2][2]), 1 + 2 * 5.0, 1e-15);
}

Model one_body(const Mat3& inertia) {
  Model m;
  m.file = "bad.yaml";
  Body b;
  b.name = "wing";
  b.mass = 1;
  b.inertia = inertia;
  b.loc = {"bad.yaml", 7, 3};
  b.make_free();
  m.bodies.push_back(b);
  return m;
}

TEST(BodyInertia, NonPhysicalInertiaIsAnErrorNamingTheBody) {
  for (const Mat3& bad : {principal_inertia(-1, 2, 2), principal_inertia(1, 1, 3)}) {
    const Model m = one_body(bad);
    try {
      derive(m);
      FAIL() << "expected a ModelError";
    } catch (const ModelError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("wing"), std::string::npos) << what;
      EXPECT_NE(what.find("bad.yaml:7"), std::string::npos) << what;
    }
  }
  EXPECT_NO_THROW(derive(one_body(principal_inertia(1, 1, 2))));  // flat plate: I₁ + I₂ = I₃
}

TEST(BodyInertia, OrientationsAgree) {
  // A quarter turn about z by axis–angle, Euler yaw and quaternion.
  const Rotation a = rotation_from_axis_angle({0, 0, 2}, M_PI / 2);
  const Rotation e = rotation_from_euler(0, 0, M_PI / 2);
  const Rotation q = rotation_from_quaternion({std::cos(M_PI / 4), 0, 0, std::sin(M_PI / 4)});
  const Rotation expected{0, -1, 0, 1, 0, 0, 0, 0, 1};
  for (size_t i = 0; i < 9; ++i) {
    EXPECT_NEAR(a[i], expected[i], 1e-15);
    EXPECT_NEAR(e[i], expected[i], 1e-15);
    EXPECT_NEAR(q[i], expected[i], 1e-15);
  }
  const Rotation r = rotation_from_euler(0.3, -0.7, 1.9);
  EXPECT_LT(orthonormality_error(r.data()), 1e-15);
  EXPECT_THROW(rotation_from_axis_angle({0, 0, 0}, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange
