#pragma once
// Time derivatives used throughout the derivation (DESIGN.md §4.1, §4.3).

#include <ginac/ginac.h>

#include "lagrange/model.hpp"

namespace lagrange::symbolic {

/// Explicit time dependence: ∂e/∂t + Σ (∂e/∂u u̇ + ∂e/∂u̇ ü) over the model's inputs.
GiNaC::ex partial_t(const Model& model, const GiNaC::ex& e);

/// d/dt e with accelerations set to zero: Σⱼ ∂e/∂qⱼ vⱼ + partial_t(e).
/// For e = ẋ this is the velocity-product ("bias") acceleration of a point.
GiNaC::ex derivative_without_accelerations(const Model& model, const GiNaC::ex& e);

/// Velocity of a world point x(q, t): Σᵢ ∂x/∂qᵢ vᵢ + ∂x/∂t.
Vec3 point_velocity(const Model& model, const Vec3& x);

/// a·b for 3-vectors of expressions.
GiNaC::ex dot(const Vec3& a, const Vec3& b);

/// True when e depends on any coordinate, velocity or acceleration symbol of the model.
bool depends_on_state(const Model& model, const GiNaC::ex& e);

/// True when e depends on any velocity or acceleration symbol.
bool depends_on_rates(const Model& model, const GiNaC::ex& e);

/// True when e depends on any acceleration symbol (q̈ or ü).
bool depends_on_accelerations(const Model& model, const GiNaC::ex& e);

}  // namespace lagrange::symbolic
