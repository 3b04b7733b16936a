#pragma once
// Time derivatives used throughout the derivation (docs/theory.md §2, §4.1, §4.3).

#include <ginac/ginac.h>

#include <vector>

#include "lagrange/equations.hpp"

namespace lagrange::symbolic {

/// Explicit time dependence: ∂e/∂t + Σ (∂e/∂u u̇ + ∂e/∂u̇ ü) over the model's inputs.
GiNaC::ex partial_t(const Kinematics& kin, const GiNaC::ex& e);

/// d/dt e with accelerations set to zero: Σⱼ ∂e/∂qⱼ q̇ⱼ + partial_t(e), q̇ = K(q) v.
/// For e = ẋ this is the velocity-product ("bias") acceleration of a point.
GiNaC::ex derivative_without_accelerations(const Kinematics& kin, const GiNaC::ex& e);

/// Velocity of a world point x(q, t): Σⱼ ∂x/∂qⱼ q̇ⱼ + ∂x/∂t.
Vec3 point_velocity(const Kinematics& kin, const Vec3& x);

/// Jacobian column ∂ẋ/∂v_k = Σⱼ ∂x/∂qⱼ K_jk of a point for every velocity (∂x/∂q_k when
/// q̇ = v).
std::vector<Vec3> point_jacobian(const Kinematics& kin, const Vec3& x);

/// Generalised force of a scalar function f(q) along each velocity: (Kᵀ ∂f/∂q)_k.
std::vector<GiNaC::ex> velocity_gradient(const Kinematics& kin, const GiNaC::ex& f);

/// The state symbols in e as (role, index) pairs ('q', 'v', 'a'; Kinematics::role), sorted and
/// without repeats: one pass over e.
std::vector<std::pair<char, size_t>> state_symbols(const Kinematics& kin, const GiNaC::ex& e);
/// Indices of the coordinates qⱼ that e depends on, ascending.
std::vector<size_t> coordinates_in(const Kinematics& kin, const GiNaC::ex& e);
/// Indices of the velocities v_k that e depends on, ascending.
std::vector<size_t> velocities_in(const Kinematics& kin, const GiNaC::ex& e);

/// a·b for 3-vectors of expressions.
GiNaC::ex dot(const Vec3& a, const Vec3& b);

/// True when e depends on any coordinate, velocity or acceleration symbol of the model.
bool depends_on_state(const Kinematics& kin, const GiNaC::ex& e);

/// True when e depends on any velocity or acceleration symbol.
bool depends_on_rates(const Kinematics& kin, const GiNaC::ex& e);

/// True when e depends on any acceleration symbol (q̈ or ü).
bool depends_on_accelerations(const Kinematics& kin, const GiNaC::ex& e);

/// True when e depends on a coordinate or velocity of a free body (beyond the plain ones).
bool depends_on_body_state(const Kinematics& kin, const GiNaC::ex& e);

}  // namespace lagrange::symbolic
