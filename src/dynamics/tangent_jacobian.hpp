#pragma once
// ∂C/∂q with each free body's nine R columns replaced by its three tangent columns, as a sparse
// pattern fixed at construction: the projection's position Jacobian (docs/theory.md §4.3,
// "Consistent states").

#include <cstdint>
#include <vector>

#include "dynamics/sparse_range_space.hpp"

namespace lagrange::dynamics {

/// Columns: the coordinates outside every R (in q's order), then three per free body,
///   ∂C/∂θ_k = Σ_ic (∂C/∂R_ic) (R [e_k]×)_ic,
/// so that a step x maps back to Δq with ΔR = R [Δθ]×, tangent to SO(3).
class TangentJacobian {
 public:
  /// `Cq` the pattern of ∂C/∂q (m × nq), `rotations` where each free body's R starts in q.
  TangentJacobian(const Pattern& Cq, size_t nq, const std::vector<size_t>& rotations);

  /// (row, tangent column) of each value reduce() writes.
  const Pattern& pattern() const { return pattern_; }
  size_t columns() const { return columns_; }
  /// The tangent Jacobian's values at q from ∂C/∂q's values (in Cq's pattern order).
  void reduce(const double* cq, const double* q, double* values) const;
  /// Δq at q from a step x in the tangent columns: x itself for the coordinates outside R,
  /// ΔR = Σ_k x_k R [e_k]× for each free body.
  void expand(const double* x, const double* q, double* step) const;

 private:
  /// A value of ∂C/∂q that is a value of the tangent Jacobian (outside R).
  struct Copy {
    uint32_t value, cq;
  };
  /// One term sign · q[r] · cq of a tangent column's value: (R [e_k]×)_ic is R_{i,k+2} where
  /// c = k + 1, −R_{i,k+1} where c = k + 2 (indices mod 3), 0 otherwise.
  struct Term {
    uint32_t value, cq, r;
    double sign;
  };
  size_t columns_;
  std::vector<size_t> rotations_;
  std::vector<uint32_t> plain_;  // tangent column c < plain_.size() is coordinate plain_[c]
  Pattern pattern_;
  std::vector<Copy> copies_;
  std::vector<Term> terms_;  // grouped by value, ascending coordinate within a value
};

}  // namespace lagrange::dynamics
