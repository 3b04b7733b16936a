// The derived equations equal the seed's hand-derived ones (seed 000), checked as
// "difference normalises to zero".

#include <gtest/gtest.h>

#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::example_path;
using testing::same;
using testing::sym;

TEST(SeedEquations, PendulumThetaDdot) {
  const Model m = read_model_file(example_path("pendulum.yaml"));
  const Equations eq = derive(m);
  const auto a = solve_accelerations(eq);
  const auto g = sym(m, "g"), l = sym(m, "l"), th = sym(m, "theta");
  EXPECT_TRUE(same(a[0], -g / l * sin(th))) << a[0];
  EXPECT_TRUE(same(eq.M(0, 0), sym(m, "m") * l * l)) << eq.M(0, 0);
}

TEST(SeedEquations, ElasticPendulum) {
  const Model m = read_model_file(example_path("elastic_pendulum.yaml"));
  const Equations eq = derive(m);
  const auto a = solve_accelerations(eq);
  const auto g = sym(m, "g"), k = sym(m, "k"), mass = sym(m, "m"), l0 = sym(m, "l0");
  const auto l = sym(m, "l"), th = sym(m, "theta"), ld = sym(m, "l_dot"), thd = sym(m, "theta_dot");
  // l'' = l th'^2 + g cos th − (k/m)(l − l0);  th'' = −(g/l) sin th − (2/l) l' th'
  EXPECT_TRUE(same(a[0], l * thd * thd + g * cos(th) - k / mass * (l - l0))) << a[0];
  EXPECT_TRUE(same(a[1], -g / l * sin(th) - 2 / l * ld * thd)) << a[1];
  // The seed's d/dt(∂L/∂q̇) for θ: m l² θ̈ + 2 m l l̇ θ̇.
  const auto thdd = sym(m, "theta_ddot");
  EXPECT_TRUE(same(eq.euler_lagrange_lhs(1),
                   mass * l * l * thdd + 2 * mass * l * ld * thd + mass * g * l * sin(th)));
}

TEST(SeedEquations, InclinedPlaneVirtualWorkIsConstant) {
  const Model m = read_model_file(example_path("inclined_plane.yaml"));
  const Equations eq = derive(m);
  const auto g = sym(m, "g"), mass = sym(m, "m"), alpha = sym(m, "alpha");
  EXPECT_TRUE(same(eq.Q[0], mass * g * sin(alpha))) << eq.Q[0];
  EXPECT_FALSE(eq.Q[0].has(sym(m, "s")));
}

TEST(SeedEquations, PendulumHorizontalForceDependsOnQ) {
  const Model m = read_model_file(example_path("pendulum_horizontal_force.yaml"));
  const Equations eq = derive(m);
  const auto l = sym(m, "l"), th = sym(m, "theta"), F = sym(m, "F");
  EXPECT_TRUE(same(eq.Q[0], F * l * cos(th))) << eq.Q[0];
}

TEST(SeedEquations, ParticleAndEnergyPathsAgree) {
  // The double pendulum through point Jacobians (particles) and through a hand-written T.
  const Model particles = read_model_file(example_path("double_pendulum.yaml"));
  const Equations e1 = derive(particles);
  Model energy = particles;  // same symbols
  GiNaC::ex T = 0, U = 0;
  const Vec3 g = *energy.gravity;
  for (const auto& p : energy.particles) {
    const Point* pt = energy.find_point(p.point);
    Vec3 v;
    for (int k = 0; k < 3; ++k) v[k] = energy.time_derivative(pt->pos[k]);
    T += p.mass / 2 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    U -= p.mass * (g[0] * pt->pos[0] + g[1] * pt->pos[1] + g[2] * pt->pos[2]);
  }
  energy.particles.clear();
  energy.gravity.reset();
  energy.kinetic = T;
  energy.potential = U;
  const Equations e2 = derive(energy);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_TRUE(same(e1.h[i], e2.h[i])) << i;
    for (size_t j = 0; j < 2; ++j) EXPECT_TRUE(same(e1.M(i, j), e2.M(i, j))) << i << j;
  }
  EXPECT_TRUE(same(e1.T, e2.T));
  EXPECT_TRUE(same(e1.U, e2.U));
}

TEST(SeedEquations, ConstrainedPendulumIndexReduction) {
  const Model m = read_model_file(example_path("cartesian_pendulum.yaml"));
  const Equations eq = derive(m);
  const auto x = sym(m, "x"), y = sym(m, "y"), xd = sym(m, "x_dot"), yd = sym(m, "y_dot");
  ASSERT_EQ(eq.m, 1u);
  EXPECT_TRUE(same(eq.G(0, 0), x));
  EXPECT_TRUE(same(eq.G(0, 1), y));
  EXPECT_TRUE(same(eq.Cdot[0], x * xd + y * yd));
  EXPECT_TRUE(same(eq.c[0], xd * xd + yd * yd));
}

TEST(SeedEquations, RheonomicConstraintDifferentiatesInputs) {
  const Model m = read_model_file(example_path("crane.yaml"));
  const Equations eq = derive(m);
  // C = ((x − xc)² + y² − L²)/2 ⇒ ∂ₜC = −(x − xc) xċ − L L̇ enters Ċ.
  const auto x = sym(m, "x"), xc = sym(m, "xc"), L = sym(m, "L");
  const Input& in_xc = m.inputs[static_cast<size_t>(m.input_index("xc"))];
  const Input& in_L = m.inputs[static_cast<size_t>(m.input_index("L"))];
  const auto xd = sym(m, "x_dot"), yd = sym(m, "y_dot"), y = sym(m, "y");
  EXPECT_TRUE(same(eq.Cdot[0], (x - xc) * (xd - in_xc.ud) + y * yd - L * in_L.ud));
  EXPECT_TRUE(eq.c[0].has(in_xc.udd));
  EXPECT_TRUE(eq.c[0].has(in_L.udd));
}

}  // namespace
}  // namespace lagrange

namespace lagrange {
namespace {

TEST(SeedEquations, AbsPotentialCompilesToSignForce) {
  // d/dx |x| = sign(x). GiNaC writes it with conjugate(x); model symbols are real, so the tape
  // and simplify() treat conjugate as the identity.
  auto sys = testing::load_string(R"(
parameters: {m: 2.0, k: 3.0}
coordinates:
  x: {initial: 0.3}
points: {p: [x, 0, 0]}
particles: {p: m}
potential: k*abs(x)
)");
  const Equations eq = derive(*sys.model);
  const GiNaC::ex x = testing::sym(*sys.model, "x"), k = testing::sym(*sys.model, "k");
  EXPECT_TRUE(testing::same(eq.h[0], -k * x / abs(x))) << eq.h[0];
  for (double x : {0.3, -0.3}) {
    double qd, a;
    const double v = 0.0;
    sys.dynamics->forward(0.0, &x, &v, &qd, &a, nullptr);
    EXPECT_DOUBLE_EQ(a, x > 0 ? -1.5 : 1.5);
  }
}

}  // namespace
}  // namespace lagrange
