#pragma once
// The minimum-norm solution of an underdetermined sparse system J x = r whose pattern is fixed:
// the projection's Gauss–Newton steps (docs/theory.md §4.3, "Projecting when the drift matters").

#include <vector>

#include "dynamics/sparse_range_space.hpp"

namespace lagrange::dynamics {

/// x = Jᵀ (J Jᵀ)⁻¹ r for an m × n J given by its pattern: the KKT system [I Jᵀ; J 0] of the
/// range-space solve with M = I, so J Jᵀ's envelope and the products that fill it are worked
/// out once and a call does arithmetic only. When J Jᵀ is numerically singular (smallest pivot
/// not above 1e-12 of its largest diagonal entry: redundant rows) the rank-revealing complete
/// orthogonal decomposition of a dense copy of J answers instead (that fallback allocates).
class MinimumNorm {
 public:
  MinimumNorm(size_t n, size_t m, const Pattern& J);

  size_t rows() const { return m_; }
  size_t columns() const { return n_; }
  const Pattern& pattern() const { return J_; }
  /// x (n) from J's values in pattern order and r (m).
  void solve(const double* j_values, const double* r, double* x);

 private:
  size_t n_, m_;
  Pattern J_;
  SparseRangeSpace normal_;
  std::vector<double> ones_, zeros_, lambda_;
};

}  // namespace lagrange::dynamics
