// Reading whole model files: every section lands in the Model with the expected expressions.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>

#include "lagrange/reader.hpp"
#include "model/latex_names.hpp"
#include "support/ginac_values.hpp"

namespace lagrange {
namespace {

/// `e` with sin(x)² replaced by 1 − cos(x)² for every x, expanded.
GiNaC::ex pythagoras(const GiNaC::ex& e) {
  GiNaC::ex x = GiNaC::wild(0);
  return e.expand()
      .subs(pow(sin(x), 2) == 1 - pow(cos(x), 2), GiNaC::subs_options::algebraic)
      .expand();
}

const char* kDoublePendulum = R"(name: double pendulum
parameters: {m1: 1.0, m2: 2.0, l1: 1.0, l2: 0.5, g: 9.81, c: 0.1, k: 40, l0: 0.25}
coordinates:
  theta1: {initial: 0.5, rate: 0.0}
  theta2: {initial: l2/2, rate: -1, fixed: true}
inputs:
  F: 2*sin(3*t)
points:
  p2: p1 + [l2*sin(theta2), -l2*cos(theta2), 0]
  p1: [l1*sin(theta1), -l1*cos(theta1), 0]
  anchor: [0, 0, 0]
particles:
  - {point: p1, mass: m1}
  - {point: p2, mass: m2}
gravity: [0, -g, 0]
kinetic: m1/2*dot(vel(p1), vel(p1))
potential: m1*g*p1.y
generalized_forces: {theta2: -c*der(theta2)}
forces:
  - {point: p2, force: [F, 0, 0]}
springs:
  - {between: [anchor, p2], k: k, l0: l0}
dampers:
  - {between: [anchor, p1], c: c}
constraints:
  rod: p1.x^2 + p1.y^2 - l1^2
outputs:
  x2: p2.x
  speed1: norm(vel(p1))
stabilization: {alpha: 10, project: false, gamma: 2}
simulate: {t_end: 5, output_step: 0.02, integrator: rk4, rtol: 1e-6, atol: 1e-9, step: 0.001}
)";

TEST(YamlReader, ReadsEverySection) {
  Model m = read_model_string(kDoublePendulum, "dp.yaml");
  EXPECT_EQ(m.name, "double pendulum");
  EXPECT_EQ(m.file, "dp.yaml");
  ASSERT_EQ(m.parameters.size(), 8u);
  EXPECT_EQ(m.parameters[4].name, "g");
  EXPECT_DOUBLE_EQ(m.parameters[4].value, 9.81);
  EXPECT_EQ(m.parameters[4].loc.line, 2);
  EXPECT_EQ(m.parameters[4].loc.column, 50);

  ASSERT_EQ(m.coordinates.size(), 2u);
  const Coordinate &q1 = m.coordinates[0], &q2 = m.coordinates[1];
  EXPECT_EQ(q1.name, "theta1");
  EXPECT_EQ(q2.q.get_name(), "theta2");
  EXPECT_EQ(q2.v.get_name(), "theta2_dot");
  EXPECT_EQ(q2.a.get_name(), "theta2_ddot");
  EXPECT_DOUBLE_EQ(q2.initial, 0.25);
  EXPECT_DOUBLE_EQ(q2.rate, -1.0);
  EXPECT_FALSE(q1.fixed);
  EXPECT_TRUE(q2.fixed);
  EXPECT_EQ(q2.loc.str(), "dp.yaml:5:3");

  const auto& p = [&](const char* n) {
    return GiNaC::ex(m.parameters.at(m.parameter_index(n)).sym);
  };
  GiNaC::ex l1 = p("l1"), l2 = p("l2"), m1 = p("m1"), g = p("g"), c = p("c");
  ASSERT_EQ(m.inputs.size(), 1u);
  EXPECT_TRUE(same(m.inputs[0].expr, 2 * sin(3 * m.t)));
  EXPECT_EQ(m.inputs[0].ud.get_name(), "F_dot");

  const Point* p1 = m.find_point("p1");
  const Point* p2 = m.find_point("p2");
  ASSERT_TRUE(p1 && p2);
  EXPECT_EQ(m.points[0].name, "p2");  // kept in the order written
  EXPECT_TRUE(same(p2->pos[0], l1 * sin(q1.q) + l2 * sin(q2.q)));
  EXPECT_TRUE(same(p2->pos[1], -l1 * cos(q1.q) - l2 * cos(q2.q)));
  EXPECT_TRUE(same(p2->pos[2], 0));

  GiNaC::ex T = m1 / 2 * pow(l1 * q1.v, 2);  // |vel(p1)|² = l1² θ̇1²
  EXPECT_TRUE(same(pythagoras(m.kinetic), T));
  EXPECT_TRUE(same(m.potential, -m1 * g * l1 * cos(q1.q)));
  ASSERT_EQ(m.generalized_forces.size(), 2u);
  EXPECT_TRUE(m.generalized_forces[0].is_zero());
  EXPECT_TRUE(same(m.generalized_forces[1], -c * q2.v));

  ASSERT_EQ(m.particles.size(), 2u);
  EXPECT_EQ(m.particles[1].point, "p2");
  EXPECT_TRUE(same(m.particles[1].mass, p("m2")));
  EXPECT_EQ(m.particles[1].loc.str(), "dp.yaml:14:5");
  ASSERT_TRUE(m.gravity.has_value());
  EXPECT_TRUE(same((*m.gravity)[1], -g));
  ASSERT_EQ(m.forces.size(), 1u);
  EXPECT_TRUE(same(m.forces[0].force[0], m.inputs[0].u));
  ASSERT_EQ(m.springs.size(), 1u);
  EXPECT_EQ(m.springs[0].a, "anchor");
  EXPECT_EQ(m.springs[0].b, "p2");
  EXPECT_TRUE(same(m.springs[0].l0, p("l0")));
  ASSERT_EQ(m.dampers.size(), 1u);
  EXPECT_TRUE(same(m.dampers[0].c, c));
  ASSERT_EQ(m.constraints.size(), 1u);
  EXPECT_EQ(m.constraints[0].name, "rod");
  EXPECT_TRUE(pythagoras(m.constraints[0].expr).is_zero());
  ASSERT_EQ(m.outputs.size(), 2u);
  EXPECT_TRUE(same(m.outputs[0].expr, p2->pos[0]));
  EXPECT_EQ(m.outputs[1].loc.str(), "dp.yaml:29:3");

  EXPECT_DOUBLE_EQ(m.stabilization.alpha.value_or(-1), 10);
  EXPECT_FALSE(m.stabilization.project);
  EXPECT_DOUBLE_EQ(m.stabilization.gamma, 2);
  EXPECT_DOUBLE_EQ(m.simulate.t_end, 5);
  EXPECT_DOUBLE_EQ(m.simulate.output_step, 0.02);
  EXPECT_EQ(m.simulate.integrator, "rk4");
  EXPECT_DOUBLE_EQ(m.simulate.rtol, 1e-6);
  EXPECT_DOUBLE_EQ(m.simulate.atol, 1e-9);
  EXPECT_DOUBLE_EQ(m.simulate.step, 0.001);
}

TEST(YamlReader, VelocityAndDerivativeOfAPolarPoint) {
  Model m = read_model_string(R"(coordinates:
  r: {initial: 1}
  phi: {initial: 0}
points:
  p: [r*cos(phi), r*sin(phi), 0]
outputs:
  vx: vel(p).x
  vy: vel(p).y
  speed2: dot(vel(p), vel(p))
  ax: der(vel(p).x)
  dt: der(t^2*r)
)",
                              "polar.yaml");
  const Coordinate &r = m.coordinates[0], &phi = m.coordinates[1];
  EXPECT_TRUE(same(m.outputs[0].expr, r.v * cos(phi.q) - r.q * sin(phi.q) * phi.v));
  EXPECT_TRUE(same(m.outputs[1].expr, r.v * sin(phi.q) + r.q * cos(phi.q) * phi.v));
  GiNaC::ex speed2 = pow(r.v, 2) + pow(r.q * phi.v, 2);
  EXPECT_TRUE(same(pythagoras(m.outputs[2].expr), speed2));
  GiNaC::ex ax = r.a * cos(phi.q) - 2 * r.v * sin(phi.q) * phi.v -
                 r.q * cos(phi.q) * pow(phi.v, 2) - r.q * sin(phi.q) * phi.a;
  EXPECT_TRUE(same(m.outputs[3].expr, ax));
  EXPECT_TRUE(same(m.outputs[4].expr, 2 * m.t * r.q + pow(m.t, 2) * r.v));
}

TEST(YamlReader, ParticlesAsAMapAndDefaults) {
  Model m = read_model_string(R"(parameters: {m: 2}
coordinates:
  x: {initial: 2*pi}
points:
  a: [x, 0, 0]
particles: {a: m}
)",
                              "defaults.yaml");
  EXPECT_EQ(m.name, "defaults");
  EXPECT_NEAR(m.coordinates[0].initial, 2 * M_PI, 1e-15);
  EXPECT_DOUBLE_EQ(m.coordinates[0].rate, 0.0);
  ASSERT_EQ(m.particles.size(), 1u);
  EXPECT_EQ(m.particles[0].point, "a");
  EXPECT_TRUE(m.kinetic.is_zero());
  EXPECT_FALSE(m.gravity.has_value());
  EXPECT_EQ(m.simulate.integrator, "dop853");
  EXPECT_FALSE(m.stabilization.alpha.has_value());  // baumgarte_rate() chooses
  ASSERT_EQ(m.generalized_forces.size(), 1u);
  EXPECT_TRUE(m.generalized_forces[0].is_zero());
}

TEST(YamlReader, ReadsFilesAndReportsMissingOnes) {
  std::string path = ::testing::TempDir() + "lagrange_reader_test.yaml";
  {
    std::ofstream out(path);
    out << "coordinates:\n  x: {initial: 1}\nkinetic: x_dot\n";
  }
  try {
    read_model_file(path);
    FAIL() << "expected an error";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.loc().str(), path + ":3:10");
  }
  std::remove(path.c_str());
  EXPECT_THROW(read_model_file(path), ModelError);
  EXPECT_THROW(read_model_file(::testing::TempDir()), ModelError);
}

TEST(YamlReader, LatexNames) {
  using model::latex_name;
  EXPECT_EQ(latex_name("theta1"), "\\theta_{1}");
  EXPECT_EQ(latex_name("theta1", "\\dot"), "\\dot{\\theta}_{1}");
  EXPECT_EQ(latex_name("phi"), "\\phi");
  EXPECT_EQ(latex_name("x"), "x");
  EXPECT_EQ(latex_name("l_arm"), "l_{\\mathrm{arm}}");
  EXPECT_EQ(latex_name("mass"), "\\mathrm{mass}");
  // Element names (issue 36 item 12): the subscript braced whole, a dotted name one word.
  EXPECT_EQ(latex_name("T_drum"), "T_{\\mathrm{drum}}");
  EXPECT_EQ(latex_name("drum.reeled_out", "\\dot"), "\\dot{\\mathrm{drum.reeled\\_out}}");
  EXPECT_EQ(latex_name("Q_drum.reeled_out"), "Q_{\\mathrm{drum.reeled\\_out}}");
  Model m = read_model_string("coordinates: {psi: {initial: 0}}\n", "l.yaml");
  std::ostringstream s;
  m.coordinates[0].v.print(GiNaC::print_latex(s));
  EXPECT_EQ(s.str(), "\\dot{\\psi}");
}

}  // namespace
}  // namespace lagrange
