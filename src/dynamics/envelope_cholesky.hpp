#pragma once
// Allocation-free square-root-free Cholesky factorisation (L D Lᵀ) of a symmetric positive
// definite matrix stored by its lower envelope (profile): row i holds columns first[i] … i.
// Fill-in stays inside the envelope, so banded matrices (chains) cost O(m b²) with no allocation
// after construction.

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
  /// Matrix entries (lower envelope); overwritten by the factors on factorize() (L's strict lower
  /// triangle, D on the diagonal).
  double* values() { return values_.data(); }
  size_t num_values() const { return values_.size(); }

  /// In-place factorisation A = L D Lᵀ (L unit lower triangular). False when a pivot Dᵢ is not
  /// positive or the smallest is not above `singular_below` times the largest diagonal entry of
  /// A (numerically singular).
  bool factorize(double singular_below = 1e-13);
  /// Solve L D Lᵀ x = b in place.
  void solve(double* b) const;
  /// Solve L D Lᵀ X = B in place for k right-hand sides, B row-major (size() × k).
  void solve_rows(double* B, size_t k) const;

 private:
  std::vector<size_t> first_, offset_;
  std::vector<double> values_;
  std::vector<double> inverse_pivot_;  // 1/Dᵢ: the solves multiply instead of divide
};

}  // namespace lagrange::dynamics
