#pragma once
// Derived equations of motion (DESIGN.md §4.1–4.3), symbolic in the parameters.

#include <ginac/ginac.h>

#include <string>
#include <vector>

#include "lagrange/model.hpp"

namespace lagrange {

/// The equations of motion of a model in the form
///   M(q,t) a = h(q,v,t) + Q(q,v,t) − Gᵀλ,   C(q,t) = 0,   C̈ = G a + c,
/// with state (q, v), q̇ = qdot(q, v) (DESIGN.md §2), all symbolic in (t, q, v, u, u̇, ü, p).
struct Equations {
  const Model* model = nullptr;  ///< the model these were derived from (symbols live there)
  size_t n = 0;                  ///< number of coordinates
  size_t m = 0;                  ///< number of constraints

  GiNaC::ex T, U, L;         ///< kinetic, potential energy, L = T − U (λᵀC kept apart)
  GiNaC::matrix M;           ///< n×n mass matrix ∂²T/∂v∂vᵀ
  std::vector<GiNaC::ex> h;  ///< forcing from L: ∂L/∂q − (∂²L/∂v∂qᵀ) v − ∂²L/∂v∂t
  std::vector<GiNaC::ex> Q;     ///< non-conservative generalised forces (virtual work)
  std::vector<GiNaC::ex> qdot;  ///< kinematics q̇ = K(q) v (identity for plain coordinates)

  std::vector<GiNaC::ex> C;     ///< constraints C(q,t), m of them
  GiNaC::matrix G;              ///< m×n constraint Jacobian ∂C/∂q
  std::vector<GiNaC::ex> Cdot;  ///< Ċ = G v + ∂C/∂t
  std::vector<GiNaC::ex> c;     ///< C̈ − G a: (∂(G v)/∂q) v + 2(∂G/∂t) v + ∂²C/∂t²

  std::vector<GiNaC::ex> outputs;  ///< the model's named outputs, in order

  /// Left side of coordinate i's Euler–Lagrange equation, d/dt(∂L/∂q̇ᵢ) − ∂L/∂qᵢ = Σⱼ Mᵢⱼ aⱼ − hᵢ.
  GiNaC::ex euler_lagrange_lhs(size_t i) const;
  /// Tape input symbols in their fixed order: t, q, v, u, u̇, ü, p.
  std::vector<GiNaC::symbol> tape_inputs() const;
};

/// Derive the equations of motion of `model`: particles and point masses through point
/// Jacobians (M = Σ m JᵀJ, DESIGN.md §8), user energies through ∂²L/∂v∂vᵀ (§4.1), forces and
/// dampers by virtual work (§4.2), constraints twice differentiated (§4.3).
Equations derive(const Model& model);

/// Symbolic accelerations a = M⁻¹(h + Q) for unconstrained systems with n ≤ 4 (for display
/// and tests); normalised. Throws std::invalid_argument when constrained or n > 4.
std::vector<GiNaC::ex> solve_accelerations(const Equations& eq);

/// A canonical rational form with sin² + cos² = 1 applied (for display and for symbolic
/// equality tests: a and b are equal when simplify(a − b) is zero).
GiNaC::ex simplify(const GiNaC::ex& e);

}  // namespace lagrange
