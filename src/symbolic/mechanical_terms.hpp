#pragma once
// Accumulators for the pieces of M a = h + Q, filled by one function per kind of element.

#include <ginac/ginac.h>

#include <vector>

#include "lagrange/equations.hpp"
#include "lagrange/model.hpp"

namespace lagrange::symbolic {

/// Partial sums of the equations of motion while elements are added.
struct MechanicalTerms {
  explicit MechanicalTerms(size_t n) : M(n, n), h(n, 0), Q(n, 0) {}
  GiNaC::matrix M;
  std::vector<GiNaC::ex> h;
  std::vector<GiNaC::ex> Q;
  GiNaC::ex T = 0;
  GiNaC::ex U = 0;
};

/// Point masses at the model's particles, in gravity (DESIGN.md §8, seed 001):
/// M += Σ m JᵀJ, h += Σ m Jᵀ(g − J̇v − ∂ₜẋ), grouping equal Jacobian columns so that chains
/// give O(N²) terms. Also adds ½ m|ẋ|² to T and −m g·x to U.
void add_particle_terms(const Model& model, MechanicalTerms& terms);

/// User-written kinetic and potential energy plus springs, through the general formulas of
/// DESIGN.md §4.1: M += ∂²L/∂v∂vᵀ, h += ∂L/∂q − (∂²L/∂v∂qᵀ) v − ∂ₜ(∂L/∂v).
void add_energy_terms(const Model& model, MechanicalTerms& terms);

/// Non-conservative generalised forces: the model's per-coordinate forces, point forces by
/// virtual work Q = (∂x/∂q)ᵀF (DESIGN.md §4.2), dampers by Rayleigh dissipation.
void add_generalized_forces(const Model& model, MechanicalTerms& terms);

/// Constraints, their Jacobian G and first and second time derivatives (DESIGN.md §4.3).
void add_constraint_terms(const Model& model, Equations& eq);

/// Jacobian column ∂x/∂qᵢ of a point for every coordinate.
std::vector<Vec3> point_jacobian(const Model& model, const Vec3& x);

}  // namespace lagrange::symbolic
