#pragma once
// Memoised sparse gradients ∂e/∂q, for expressions that share terms (points of a chain).

#include <ginac/ginac.h>

#include <unordered_map>
#include <utility>
#include <vector>

#include "lagrange/equations.hpp"

namespace lagrange::symbolic {

/// Sparse gradient: (coordinate index, ∂e/∂qᵢ) for the coordinates e depends on.
using SparseGradient = std::vector<std::pair<size_t, GiNaC::ex>>;

/// Gradients of sums are sums of their terms' gradients, and terms are memoised by value, so
/// that a chain point (its parent's terms plus one link) costs O(1) new differentiations:
/// docs/theory.md §8, "build each point's Jacobian from its parent's" — O(N²) for N-link chains.
class GradientCache {
 public:
  explicit GradientCache(const Kinematics& kin);

  /// ∂e/∂q for the coordinates e depends on, in coordinate order.
  const SparseGradient& gradient(const GiNaC::ex& e);
  /// Dense Jacobian columns ∂ẋ/∂v_k = Σⱼ ∂x/∂qⱼ K_jk of a point (∂x/∂q_k when q̇ = v).
  std::vector<Vec3> jacobian(const Vec3& x);
  /// d/dt e with accelerations zero: Σ ∂e/∂qⱼ q̇ⱼ + ∂ₜe (see time_partials.hpp).
  GiNaC::ex rate(const GiNaC::ex& e);

 private:
  struct Hash {
    size_t operator()(const GiNaC::ex& e) const { return e.gethash(); }
  };
  struct Equal {
    bool operator()(const GiNaC::ex& a, const GiNaC::ex& b) const { return a.is_equal(b); }
  };
  SparseGradient compute(const GiNaC::ex& e);

  const Kinematics& kin_;
  std::unordered_map<GiNaC::ex, size_t, Hash, Equal> coordinate_of_;  // q symbol → index
  std::unordered_map<GiNaC::ex, SparseGradient, Hash, Equal> memo_;
};

}  // namespace lagrange::symbolic
