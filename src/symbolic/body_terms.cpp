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

// ω = U(Ω) = ½(Ω₃₂ − Ω₂₃, Ω₁₃ − Ω₃₁, Ω₂₁ − Ω₁₂), each simplified (sin² + cos² = 1) within
// kDerivationTerms (issue 37 item 12): the normal form of a rotation composed of many turns grows
// exponentially; beyond, ω is kept as given.
template <class Omega>
Vec3 unskew(const Omega& Omega_) {
  const auto simplified = [](const GiNaC::ex& e) { return simplify_within(e, kDerivationTerms); };
  return {simplified((Omega_(2, 1) - Omega_(1, 2)) / 2),
          simplified((Omega_(0, 2) - Omega_(2, 0)) / 2),
          simplified((Omega_(1, 0) - Omega_(0, 1)) / 2)};
}

// A body posed on a free body (issue 36 item 9): a rotation R_c = R M with R the free body's
// symbols and M free of every free body's R (`rotation: top.R*rot_z(q)`). Then
// R_cᵀṘ_c = Mᵀ(RᵀR)(Ω + Ξ)M + MᵀṀ, which on SO(3) (RᵀR = 1, where Ξ = 0 and, with RᵀR
// stationary, Ξ̇ = 0) is MᵀΩM + MᵀṀ: ω_c = Mᵀω + U(MᵀṀ). Its value, its partials in the
// velocities and its time derivative there are those of U(R_cᵀṘ_c), whose expansion in the nine
// entries of R and the adjugate in Ξ grew without bound (a 634 KB `derive`). nullopt when R_c is
// not of that form.
std::optional<Vec3> on_free_body(const Kinematics& kin, const Body& body) {
  const Model& model = *kin.model;
  const auto uses_free_rotation = [&](const GiNaC::ex& e, const Body& f) {
    for (const GiNaC::symbol& s : f.R)
      if (e.has(s)) return true;
    return false;
  };
  const Body* parent = nullptr;
  for (const Body& f : model.bodies) {
    if (!f.free) continue;
    for (const Vec3& row : body.rotation)
      for (const GiNaC::ex& e : row)
        if (uses_free_rotation(e, f)) {
          if (parent && parent != &f) return std::nullopt;  // posed on two free bodies
          parent = &f;
        }
  }
  if (!parent) return std::nullopt;
  const Mat3 R = parent->rot();
  Mat3 M;  // M[l][j] = ∂R_c[0][j]/∂R[0][l]
  for (size_t l = 0; l < 3; ++l)
    for (size_t j = 0; j < 3; ++j) {
      M[l][j] = body.rotation[0][j].diff(parent->R[l]).expand();
      for (const Body& f : model.bodies)
        if (f.free && uses_free_rotation(M[l][j], f)) return std::nullopt;
    }
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) {
      GiNaC::ex rest = body.rotation[i][j];
      for (size_t l = 0; l < 3; ++l) rest -= R[i][l] * M[l][j];
      if (!rest.expand().is_zero()) return std::nullopt;
    }
  Mat3 Md;
  for (size_t l = 0; l < 3; ++l)
    for (size_t j = 0; j < 3; ++j) Md[l][j] = derivative_without_accelerations(kin, M[l][j]);
  const Vec3 w{parent->w[0], parent->w[1], parent->w[2]};
  const Vec3 carried = mat_t_vec(M, w);
  const Vec3 own = unskew([&](size_t i, size_t j) {
    return M[0][i] * Md[0][j] + M[1][i] * Md[1][j] + M[2][i] * Md[2][j];
  });
  return Vec3{carried[0] + own[0], carried[1] + own[1], carried[2] + own[2]};
}

// The kinematics with each free body's Ṙ = RΩ, without the drift correction Ξ = (γ/2)((RᵀR)⁻¹ −
// 1) of Ṙ = R(Ω + Ξ) (docs/theory.md §4.4), for the bodies' inertial terms (issue 36 item 9).
// On SO(3) Ξ = 0, and Ξ̇ = 0 since RᵀR is stationary there, while ∂Ξ/∂v = 0 everywhere: the
// centre-of-mass velocities, their Jacobians and their time derivatives at a = 0 keep their
// values there, without the adjugate and determinant of RᵀR in every body posed on a free body.
// (The state's own q̇ and the constraints keep Ξ, which pulls R back onto SO(3).)
Kinematics on_rotations(const Kinematics& kin) {
  Kinematics k = kin;
  for (const Body& b : kin.model->bodies) {
    if (!b.free) continue;
    const Mat3 R = b.rot();
    const Mat3 W{Vec3{0, -b.w[2], b.w[1]}, Vec3{b.w[2], 0, -b.w[0]}, Vec3{-b.w[1], b.w[0], 0}};
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        GiNaC::ex e = 0;
        for (size_t l = 0; l < 3; ++l) e += R[i][l] * W[l][j];
        k.qdot[kin.role.at(b.R[3 * i + j]).second] = e;
      }
  }
  return k;
}

}  // namespace

// docs/theory.md §4.4: Ω = RᵀṘ, ω = U(Ω) = ½(Ω₃₂ − Ω₂₃, Ω₁₃ − Ω₃₁, Ω₂₁ − Ω₁₂).
Vec3 body_angular_velocity(const Kinematics& kin, const Body& body) {
  if (body.free) return {body.w[0], body.w[1], body.w[2]};
  if (body.angular_velocity) return *body.angular_velocity;
  if (const std::optional<Vec3> w = on_free_body(kin, body)) return *w;
  const Mat3 R = body.rotation;
  Mat3 Rd;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) Rd[i][j] = derivative_without_accelerations(kin, R[i][j]);
  return unskew([&](size_t i, size_t j) {
    return R[0][i] * Rd[0][j] + R[1][i] * Rd[1][j] + R[2][i] * Rd[2][j];
  });
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
void add_body_terms(const Kinematics& state_kin, MechanicalTerms& terms) {
  const Kinematics kin = state_kin.has_gamma ? on_rotations(state_kin) : state_kin;
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
      if (!model::is_zero(Jc[k]) || !model::is_zero(Jw[k])) active.push_back(k);
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
