#pragma once
// Model generators for the benchmark families (docs/theory.md §8, docs/benchmarks.md "Peers"): YAML text for any N.

#include <cstddef>
#include <string>

namespace lagrange::bench {

/// How the N-link pendulum's parameters are declared.
enum class PendulumParameters {
  /// One mass m and one length l shared by all links (the model of the peer figures in docs/benchmarks.md). Symbolic sums
  /// such as Σₖ m fold to (N − j)·m during derivation.
  Shared,
  /// Per-link masses m1..mN and lengths l1..lN with distinct values: nothing folds
  /// symbolically, the harder and fairer case for a symbolic engine (docs/theory.md §8).
  PerLink,
};

/// Planar N-link pendulum with absolute angles th1..thN and point masses at the link ends:
///   p1 = [l1 sin th1, −l1 cos th1, 0],  pₖ = pₖ₋₁ + [lₖ sin thₖ, −lₖ cos thₖ, 0],
/// gravity along −y. Initial angles initial_angle(k), initial rates 0. Throws
/// std::invalid_argument when n is 0.
std::string n_link_pendulum_yaml(std::size_t n,
                                 PendulumParameters parameters = PendulumParameters::PerLink);

/// Initial angle of link k (1-based): 0.5 − 0.1·(k mod 4) rad. Neighbouring links differ, so
/// that no sin(θᵢ − θⱼ) vanishes and the velocity terms are exercised.
double initial_angle(std::size_t k);
/// Mass of link k (1-based) in the PerLink family: 1 + 0.1·(k mod 7).
double per_link_mass(std::size_t k);
/// Length of link k (1-based) in the PerLink family: 0.5 + 0.05·(k mod 5).
double per_link_length(std::size_t k);

/// The same pendulum (PerLink masses and lengths) as a `links:` chain in relative joint angles
/// q1..qN (revolute about z; link k's frame at joint k, its point mass m_k at [0, −l_k, 0] with
/// principal inertia `inertia` about it), so that the absolute angle th_k = q1 + … + qk. Initial
/// absolute angles initial_angle(k), rates 0: the state of n_link_pendulum_yaml. Throws
/// std::invalid_argument when n is 0.
std::string links_chain_yaml(std::size_t n, double inertia = 0.0);

/// Planar N-link chain in Cartesian coordinates x1, y1, …, xN, yN with a particle of mass m at
/// each joint and one rod constraint per link,
///   rodₖ: ((xₖ − xₖ₋₁)² + (yₖ − yₖ₋₁)² − l²)/2,   x₀ = y₀ = 0,
/// gravity along −y, l = 0.5. The initial state hangs straight at `angle` rad from the vertical
/// (consistent with the constraints), at rest. Throws std::invalid_argument when n is 0.
std::string cartesian_chain_yaml(std::size_t n, double angle = 0.5);

}  // namespace lagrange::bench
