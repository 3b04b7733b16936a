#pragma once
// Allocation-free Cholesky factorisation of a symmetric positive definite matrix stored by its
// lower envelope (profile): row i holds columns first[i] … i. Fill-in stays inside the envelope,
// so banded matrices (chains) cost O(m b²) with no allocation after construction.

#include <cstddef>
#include <vector>

namespace lagrange::dynamics {

class EnvelopeCholesky {
 public:
  /// `first[i]` is the first column of row i that may be non-zero (first[i] ≤ i).
  explicit EnvelopeCholesky(std::vector<size_t> first);

  size_t size() const { return first_.size(); }
  /// Position of entry (i, j), first[i] ≤ j ≤ i, in values().
  size_t index(size_t i, size_t j) const { return offset_[i] + (j - first_[i]); }
  /// Matrix entries (lower envelope); overwritten by L on factorize().
  double* values() { return values_.data(); }
  size_t num_values() const { return values_.size(); }

  /// In-place factorisation A = L Lᵀ. False when a pivot is not positive or the smallest
  /// squared pivot is below 1e-13 of the largest diagonal entry (numerically singular).
  bool factorize();
  /// Solve L Lᵀ x = b in place.
  void solve(double* b) const;
  /// Solve L Lᵀ X = B in place for k right-hand sides, B row-major (size() × k).
  void solve_rows(double* B, size_t k) const;

 private:
  std::vector<size_t> first_, offset_;
  std::vector<double> values_;
};

}  // namespace lagrange::dynamics
