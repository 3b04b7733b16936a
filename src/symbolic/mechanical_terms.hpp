#pragma once
// Accumulators for the pieces of M a = h + Q, filled by one function per kind of element.

#include <ginac/ginac.h>

#include <vector>

#include "lagrange/equations.hpp"
#include "lagrange/model.hpp"

namespace lagrange::symbolic {

/// Partial sums of the equations of motion (against the velocities v) while elements are added.
struct MechanicalTerms {
  explicit MechanicalTerms(size_t nv) : M(nv, nv), h(nv, 0), Q(nv, 0) {}
  GiNaC::matrix M;
  std::vector<GiNaC::ex> h;
  std::vector<GiNaC::ex> Q;
  GiNaC::ex T = 0;
  GiNaC::ex U = 0;
};

/// Point masses at the model's particles, in gravity (docs/theory.md §8, seed 001):
/// M += Σ m JᵀJ, h += Σ m Jᵀ(g − J̇v − ∂ₜẋ), grouping equal Jacobian columns so that chains
/// give O(N²) terms. Also adds ½ m|ẋ|² to T and −m g·x to U.
void add_particle_terms(const Kinematics& kin, MechanicalTerms& terms);

/// User-written kinetic and potential energy plus springs, through the general formulas of
/// docs/theory.md §4.1: M += ∂²L/∂v∂vᵀ, h += ∂L/∂q − (∂²L/∂v∂qᵀ) v − ∂ₜ(∂L/∂v) over the plain
/// coordinates; a potential in free-body coordinates adds h −= Kᵀ ∂U/∂q (§4.4: 2P(∂U/∂R)).
void add_energy_terms(const Kinematics& kin, MechanicalTerms& terms);

/// Rigid bodies (docs/theory.md §4.4) by virtual power, with ω (body frame) = J_ω v + ω₀ and
/// α_b = dω/dt at a = 0: M += m J_cᵀJ_c + J_ωᵀ I J_ω, h += m J_cᵀ(g − b_c) − J_ωᵀ(I α_b + ω × Iω),
/// T += ½ m|ẋ_c|² + ½ ωᵀIω, U −= m g·x_c (x_c the centre of mass). Torques: Q += J_ωᵀ τ_body.
void add_body_terms(const Kinematics& kin, MechanicalTerms& terms);

/// Non-conservative generalised forces: the model's per-coordinate forces, point forces by
/// virtual work Q = (∂x/∂q)ᵀF (docs/theory.md §4.2), dampers by Rayleigh dissipation.
void add_generalized_forces(const Kinematics& kin, MechanicalTerms& terms);

/// Constraints, their Jacobian G and first and second time derivatives (docs/theory.md §4.3),
/// with the ω-rows 2P(∂C/∂R) for free bodies (§4.4) coming from G = ∂Ċ/∂v.
void add_constraint_terms(const Kinematics& kin, Equations& eq);

/// The recursive formulation (docs/theory.md §4.9): eq.h = accelerations from the
/// articulated-body algorithm on Model::tree with its intermediates in eq.definitions, the
/// model's other forces and potentials as joint forces; eq.T, eq.U for the observables.
void add_recursive_terms(const Kinematics& kin, Equations& eq);

/// Body-frame angular velocity ω of a body: its symbols when free, else unskew(RᵀṘ) (§4.4).
Vec3 body_angular_velocity(const Kinematics& kin, const Body& body);

}  // namespace lagrange::symbolic
