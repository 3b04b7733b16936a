#include <optional>

#include "lagrange/error.hpp"
#include "lagrange/rigid_body.hpp"
#include "model/vec3_algebra.hpp"
#include "symbolic/expansion_bound.hpp"
#include "symbolic/mechanical_terms.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

using model::cross;
using model::mat_t_vec;
using model::mat_vec;

namespace {

bool is_zero(const Vec3& v) {
  return v[0].is_zero() && v[1].is_zero() && v[2].is_zero();
}

}  // namespace

// docs/theory.md §4.4: Ω = RᵀṘ, ω = U(Ω) = ½(Ω₃₂ − Ω₂₃, Ω₁₃ − Ω₃₁, Ω₂₁ − Ω₁₂).
Vec3 body_angular_velocity(const Kinematics& kin, const Body& body) {
  if (body.free) return {body.w[0], body.w[1], body.w[2]};
  if (body.angular_velocity) return *body.angular_velocity;
  const Mat3 R = body.rotation;
  Mat3 Rd;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) Rd[i][j] = derivative_without_accelerations(kin, R[i][j]);
  auto Omega = [&](size_t i, size_t j) {
    return R[0][i] * Rd[0][j] + R[1][i] * Rd[1][j] + R[2][i] * Rd[2][j];
  };
  // Simplified (sin² + cos² = 1) within kDerivationTerms (issue 37 item 12): the normal form of
  // a rotation composed of many turns grows exponentially; beyond, ω is kept as RᵀṘ gives it.
  const auto simplified = [](const GiNaC::ex& e) { return simplify_within(e, kDerivationTerms); };
  return {simplified((Omega(2, 1) - Omega(1, 2)) / 2), simplified((Omega(0, 2) - Omega(2, 0)) / 2),
          simplified((Omega(1, 0) - Omega(0, 1)) / 2)};
}

// The one component of ω that is not identically zero (z for a body posed by rot_z(q)), if any.
std::optional<size_t> single_axis(const Vec3& w) {
  std::optional<size_t> axis;
  for (size_t l = 0; l < 3; ++l)
    if (!w[l].is_zero()) {
      if (axis) return std::nullopt;
      axis = l;
    }
  return axis;
}

// docs/theory.md §4.4 by virtual power (Kane's form): with the centre of mass x_c = r + R c,
// J_c = ∂ẋ_c/∂v, b_c = dẋ_c/dt at a = 0, J_ω = ∂ω/∂v and α_b = dω/dt at a = 0,
//   M += m J_cᵀJ_c + J_ωᵀ I J_ω,   h += m J_cᵀ(g − b_c) − J_ωᵀ(I α_b + ω × Iω).
// For a free body J_ω selects ω and α_b = 0, which gives J ω̇ + ω × Jω = F_rot; forces on
// body points and constraints C(r, R) enter through ∂Ṙ/∂ω = R[eₗ]×, i.e. the 2P(·) rows.
void add_body_terms(const Kinematics& kin, MechanicalTerms& terms) {
  const Model& model = *kin.model;
  const size_t nv = kin.v.size();
  const Vec3 g = model.gravity.value_or(Vec3{0, 0, 0});
  for (const auto& body : model.bodies) {
    const Vec3 w = body_angular_velocity(kin, body);
    check_body_inertia(model, body, single_axis(w));
    if (depends_on_state(kin, body.mass))
      throw ModelError(body.loc, "the mass of body '" + body.name + "' depends on the state");
    const GiNaC::ex& m = body.mass;
    const Mat3& I = body.inertia;
    const Vec3 xc = body.world_point(body.com);
    const Vec3 vc = point_velocity(kin, xc);
    const std::vector<Vec3> Jc = point_jacobian(kin, xc);
    Vec3 force;  // m (g − b_c)
    for (size_t k = 0; k < 3; ++k)
      force[k] = m * (g[k] - derivative_without_accelerations(kin, vc[k]));
    std::vector<Vec3> Jw(nv);
    for (size_t k = 0; k < nv; ++k)
      for (size_t l = 0; l < 3; ++l) Jw[k][l] = w[l].has(kin.v[k]) ? w[l].diff(kin.v[k]) : 0;
    Vec3 alpha;
    for (size_t l = 0; l < 3; ++l) alpha[l] = derivative_without_accelerations(kin, w[l]);
    const Vec3 Iw = mat_vec(I, w);
    const Vec3 Ia = mat_vec(I, alpha);
    const Vec3 gyro = cross(w, Iw);
    Vec3 moment;  // −(I α_b + ω × Iω)
    for (size_t l = 0; l < 3; ++l) moment[l] = -(Ia[l] + gyro[l]);
    terms.T += m / 2 * dot(vc, vc) + dot(w, Iw) / 2;
    terms.U -= m * dot(g, xc);

    std::vector<size_t> active;
    for (size_t k = 0; k < nv; ++k)
      if (!is_zero(Jc[k]) || !is_zero(Jw[k])) active.push_back(k);
    for (size_t a = 0; a < active.size(); ++a) {
      const size_t i = active[a];
      const Vec3 IJi = mat_vec(I, Jw[i]);
      terms.h[i] += dot(Jc[i], force) + dot(Jw[i], moment);
      for (size_t b = a; b < active.size(); ++b) {
        const size_t j = active[b];
        const GiNaC::ex mij = m * dot(Jc[i], Jc[j]) + dot(Jw[j], IJi);
        terms.M(i, j) += mij;
        if (i != j) terms.M(j, i) += mij;
      }
    }
    // Torques by virtual power τ·ω_world = (Rᵀτ)·ω (docs/theory.md §4.4: F_rot = 2P(F_R)).
    for (const auto& tq : model.torques) {
      if (tq.body != body.name) continue;
      for (const auto& e : tq.torque)
        if (depends_on_accelerations(kin, e))
          throw ModelError(tq.loc, "the torque on '" + tq.body + "' depends on accelerations");
      const Vec3 tb = tq.body_frame ? tq.torque : mat_t_vec(body.rot(), tq.torque);
      for (size_t k : active) terms.Q[k] += dot(Jw[k], tb);
    }
  }
  for (const auto& tq : model.torques)
    if (model.find_body(tq.body) == nullptr)
      throw ModelError(tq.loc, "unknown body '" + tq.body + "' in torque");
}

}  // namespace lagrange::symbolic
