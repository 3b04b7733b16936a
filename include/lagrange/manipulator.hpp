#pragma once
// The manipulator form D(q) q̈ + C(q, q̇) q̇ + g(q) = τ (docs/theory.md §4.8) of any unconstrained
// model whose coordinates are all plain (q̇ = v), computed from its derived M and U.

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "lagrange/equations.hpp"

namespace lagrange {

/// One Christoffel symbol c_ijk = ½(∂d_kj/∂qᵢ + ∂d_ki/∂qⱼ − ∂d_ij/∂q_k), 0-based indices.
struct Christoffel {
  size_t i, j, k;
  GiNaC::ex value;
};

/// A link's Jacobians (a posed body's): its centre of mass moves with v_c = J_v q̇ and it turns
/// with ω = J_ω q̇ in world axes (docs/theory.md §4.8), D = Σ m J_vᵀJ_v + J_ωᵀ R I Rᵀ J_ω.
struct LinkJacobian {
  std::string link;
  GiNaC::matrix Jv, Jw;  ///< 3 × n each
};

/// D = M, the non-zero Christoffel symbols (both orders of i, j), C_kj = Σᵢ c_ijk q̇ᵢ, g = ∂U/∂q
/// and τ = Q (joint torques, damping, any generalised force), all symbolic in the parameters.
struct ManipulatorForm {
  const Equations* eq = nullptr;
  GiNaC::matrix D, C;
  std::vector<Christoffel> christoffel;
  std::vector<GiNaC::ex> g, tau;
  std::vector<LinkJacobian> jacobians;  ///< one per posed body (link with mass), model order
};

/// The manipulator form of `eq`. Throws std::invalid_argument, saying why, when the model has
/// constraints or free bodies, when D depends on t or inputs, or when the forcing h has terms
/// other than −C q̇ − g (a kinetic energy linear in q̇, a moving base).
ManipulatorForm manipulator_form(const Equations& eq);

/// Ḋ − 2C, skew-symmetric for every manipulator (docs/theory.md §4.8).
GiNaC::matrix d_dot_minus_2c(const ManipulatorForm& form);

/// lagrange::simplify after expanding sin and cos of sums (cos(q1 + q2) → cos q1 cos q2 − …), so
/// that products of joint rotations reduce (sin q1 sin(q1 + q2) + cos q1 cos(q1 + q2) → cos q2).
GiNaC::ex trig_simplify(const GiNaC::ex& e);

}  // namespace lagrange
