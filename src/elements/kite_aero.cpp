// Aerodynamic building blocks of the kites (docs/theory.md §4.7).

#include "elements/kite.hpp"

namespace lagrange::elements {

Vec3 cross3(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
GiNaC::ex dot_product(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec3 scaled(const GiNaC::ex& s, const Vec3& a) {
  return {s * a[0], s * a[1], s * a[2]};
}
Vec3 minus(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
GiNaC::ex length3(const Vec3& a) {
  return GiNaC::sqrt(dot_product(a, a));
}

// The ISA troposphere (awebox atmosphere.py): T = T₀ − γh, ρ = ρ₀ (T/T₀)^(g/(γR) − 1). All
// constants are exact rationals so that the tape holds no rounded numbers.
GiNaC::ex isa_density(const GiNaC::ex& height) {
  const GiNaC::numeric rho0(49, 40), t0(28815, 100), lapse(65, 10000), gas(287053, 1000),
      g(981, 100);
  const GiNaC::numeric exponent = g / (lapse * gas) - 1;
  return rho0 * GiNaC::pow(1 - lapse * height / t0, exponent);
}

// awebox three_dof_kite.py with u_a = −v_a: ê_D = û_a, ê_0 = (t × u_a)/|t × u_a| (the span at
// zero roll), ê_n = ê_D × ê_0 (in the plane of t and u_a, ⟂ u_a), ê_L = cos ψ ê_n − sin ψ ê_0.
Vec3 point_mass_lift_direction(const Vec3& v_a, const Vec3& tether, const GiNaC::ex& roll) {
  const Vec3 u_a = scaled(-1, v_a);
  const Vec3 span = cross3(tether, u_a);
  const Vec3 e0 = scaled(1 / length3(span), span);
  const Vec3 ed = scaled(1 / length3(u_a), u_a);
  const Vec3 en = cross3(ed, e0);
  Vec3 lift;
  for (size_t k = 0; k < 3; ++k) lift[k] = GiNaC::cos(roll) * en[k] - GiNaC::sin(roll) * e0[k];
  return lift;
}

FlowAngles flow_angles(const Vec3& v_body) {
  const GiNaC::ex speed = length3(v_body);
  return {GiNaC::atan2(v_body[2], v_body[0]), GiNaC::asin(v_body[1] / speed), speed};
}

}  // namespace lagrange::elements
