#pragma once
// Rigid-body models built through the C++ model API (docs/theory.md §4.4), shared by the tests:
// a free brick, a compound pendulum (SO(3) + pivot constraint, and planar with one angle) and
// a heavy top (SO(3) + pivot constraint, and Euler angles with hand-written energies).

#include <cmath>
#include <memory>
#include <string>

#include "lagrange/model.hpp"
#include "lagrange/rigid_body.hpp"
#include "model/expression_algebra.hpp"
#include "model/vec3_algebra.hpp"

namespace lagrange::testing {

inline Parameter param(const std::string& name, double value) {
  return Parameter{name, GiNaC::symbol(name), value, {}};
}

/// Rotations about z and x, and their products (the engine's own, src/model).
inline Mat3 rot_z(const GiNaC::ex& a) {
  return model::axis_rotation(2, a);
}
inline Mat3 rot_x(const GiNaC::ex& a) {
  return model::axis_rotation(0, a);
}
using model::mat_mul;
/// Numeric value of a constant rotation expression, row-major.
inline Rotation numeric(const Mat3& R) {
  Rotation out;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      out[3 * i + j] = GiNaC::ex_to<GiNaC::numeric>(R[i][j].evalf()).to_double();
  return out;
}

/// A free body with principal moments (i1, i2, i3) spinning at body-frame ω0, no forces.
inline std::unique_ptr<Model> free_brick(double i1, double i2, double i3,
                                         std::array<double, 3> w0) {
  auto m = std::make_unique<Model>();
  m->name = "brick";
  Body b;
  b.name = "brick";
  b.mass = 1;
  b.inertia = principal_inertia(i1, i2, i3);
  b.make_free();
  b.w0 = w0;
  m->bodies.push_back(b);
  return m;
}

/// Compound pendulum: a bar of mass m, length l along its body y axis, centre of mass at the
/// body origin, pivot at body point (0, l/2, 0) held at the world origin; gravity −g ŷ.
/// Starts at angle theta0 about z with rate omega0.
inline std::unique_ptr<Model> compound_pendulum_so3(double theta0, double omega0) {
  auto m = std::make_unique<Model>();
  m->name = "compound pendulum";
  m->parameters = {param("m", 2.0), param("l", 1.0), param("g", 9.81)};
  const GiNaC::ex M = m->parameters[0].sym, l = m->parameters[1].sym, g = m->parameters[2].sym;
  Body b;
  b.name = "bar";
  b.mass = M;
  b.inertia = box_inertia(M, GiNaC::numeric(1, 20), l, GiNaC::numeric(1, 20));
  b.make_free();
  b.R0 = numeric(rot_z(theta0));
  b.r0 = {0.5 * std::sin(theta0), -0.5 * std::cos(theta0), 0.0};  // r = −R p, l = 1
  b.v0 = {0.5 * omega0 * std::cos(theta0), 0.5 * omega0 * std::sin(theta0), 0.0};
  b.w0 = {0, 0, omega0};
  m->bodies.push_back(b);
  const Vec3 pivot = b.world_point({0, l / 2, 0});
  m->points.push_back(Point{"bar.pivot", pivot, {}});
  const char* names[3] = {"pivot_x", "pivot_y", "pivot_z"};
  for (size_t k = 0; k < 3; ++k) m->constraints.push_back(NamedExpr{names[k], pivot[k], {}});
  m->gravity = Vec3{0, -g, 0};
  return m;
}

/// The same bar posed by one angle: R = R_z(θ), centre of mass at R_z(θ)(0, −l/2, 0).
inline std::unique_ptr<Model> compound_pendulum_planar(double theta0, double omega0) {
  auto m = std::make_unique<Model>();
  m->name = "compound pendulum (planar)";
  m->parameters = {param("m", 2.0), param("l", 1.0), param("g", 9.81)};
  const GiNaC::ex M = m->parameters[0].sym, l = m->parameters[1].sym, g = m->parameters[2].sym;
  Coordinate th{"theta",
                GiNaC::symbol("theta"),
                GiNaC::symbol("theta_dot"),
                GiNaC::symbol("theta_ddot"),
                theta0,
                omega0,
                false,
                {}};
  m->coordinates.push_back(th);
  Body b;
  b.name = "bar";
  b.mass = M;
  b.inertia = box_inertia(M, GiNaC::numeric(1, 20), l, GiNaC::numeric(1, 20));
  b.rotation = rot_z(th.q);
  b.position = {l / 2 * sin(th.q), -l / 2 * cos(th.q), 0};
  m->bodies.push_back(b);
  m->gravity = Vec3{0, -g, 0};
  return m;
}

/// Heavy symmetric top: centre of mass at the body origin, pivot at body point (0, 0, −d) held
/// at the world origin, gravity −g ẑ; initial attitude R_z(φ) R_x(θ) R_z(ψ) (z-x-z Euler angles)
/// with Euler rates (φ̇, θ̇, ψ̇).
struct TopSetup {
  double m = 1.0, g = 9.81, d = 0.1, i1 = 0.006, i3 = 0.01;
  double phi = 0.0, theta = 0.5, psi = 0.0, phid = 0.0, thetad = 0.0, psid = 200.0;
};

inline std::unique_ptr<Model> heavy_top_so3(const TopSetup& s) {
  auto m = std::make_unique<Model>();
  m->name = "heavy top";
  Body b;
  b.name = "top";
  b.mass = s.m;
  b.inertia = principal_inertia(s.i1, s.i1, s.i3);
  b.make_free();
  const Rotation R = numeric(mat_mul(mat_mul(rot_z(s.phi), rot_x(s.theta)), rot_z(s.psi)));
  b.R0 = R;
  b.r0 = {R[2] * s.d, R[5] * s.d, R[8] * s.d};  // r = −R p = d R ẑ
  const double st = std::sin(s.theta), ct = std::cos(s.theta), sp = std::sin(s.psi),
               cp = std::cos(s.psi);
  b.w0 = {s.phid * st * sp + s.thetad * cp, s.phid * st * cp - s.thetad * sp, s.phid * ct + s.psid};
  // ṙ = R (ω × d ẑ)
  const std::array<double, 3> wxd{b.w0[1] * s.d, -b.w0[0] * s.d, 0.0};
  for (size_t i = 0; i < 3; ++i) b.v0[i] = R[3 * i] * wxd[0] + R[3 * i + 1] * wxd[1];
  m->bodies.push_back(b);
  const Vec3 pivot = b.world_point({0, 0, -s.d});
  const char* names[3] = {"pivot_x", "pivot_y", "pivot_z"};
  for (size_t k = 0; k < 3; ++k) m->constraints.push_back(NamedExpr{names[k], pivot[k], {}});
  m->gravity = Vec3{0, 0, -s.g};
  return m;
}

/// The top in z-x-z Euler angles with hand-written T and U (generic Euler–Lagrange path):
/// T = ½ I₁'(θ̇² + φ̇² sin²θ) + ½ I₃(ψ̇ + φ̇ cos θ)², I₁' = I₁ + m d², U = m g d cos θ.
inline std::unique_ptr<Model> heavy_top_euler(const TopSetup& s) {
  auto m = std::make_unique<Model>();
  m->name = "heavy top (Euler angles)";
  auto coord = [](const std::string& n, double q0, double v0) {
    return Coordinate{
        n, GiNaC::symbol(n), GiNaC::symbol(n + "_dot"), GiNaC::symbol(n + "_ddot"), q0, v0, false,
        {}};
  };
  m->coordinates = {coord("phi", s.phi, s.phid), coord("theta", s.theta, s.thetad),
                    coord("psi", s.psi, s.psid)};
  const auto& ph = m->coordinates[0];
  const auto& th = m->coordinates[1];
  const auto& ps = m->coordinates[2];
  const double i1p = s.i1 + s.m * s.d * s.d;
  m->kinetic = i1p / 2 * (th.v * th.v + ph.v * ph.v * sin(th.q) * sin(th.q)) +
               s.i3 / 2 * GiNaC::pow(ps.v + ph.v * cos(th.q), 2);
  m->potential = s.m * s.g * s.d * cos(th.q);
  return m;
}

}  // namespace lagrange::testing
