#include "dynamics/envelope_cholesky.hpp"

#include <algorithm>
#include <cmath>

namespace lagrange::dynamics {

EnvelopeCholesky::EnvelopeCholesky(std::vector<size_t> first) : first_(std::move(first)) {
  offset_.resize(first_.size());
  size_t total = 0;
  for (size_t i = 0; i < first_.size(); ++i) {
    offset_[i] = total;
    total += i - first_[i] + 1;
  }
  values_.assign(total, 0.0);
  inverse_pivot_.assign(first_.size(), 0.0);
}

// docs/theory.md §4.3, "The KKT solve without per-call overhead": row-oriented envelope L D Lᵀ.
// With W_ij = L_ij D_j, W_ij = A_ij − Σ_{k<j} W_ik L_jk over the overlap of the two rows'
// envelopes, then L_ij = W_ij / D_j and D_i = A_ii − Σ_{j<i} W_ij L_ij. No square root, and the
// divisions by D_j become products with the stored 1/D_j, so a banded row costs one division on
// its critical path.
bool EnvelopeCholesky::factorize(double singular_below) {
  double max_diag = 0.0, min_pivot = INFINITY, previous_inverse = 0.0;
  for (size_t i = 0; i < first_.size(); ++i)
    max_diag = std::max(max_diag, std::abs(values_[index(i, i)]));
  for (size_t i = 0; i < first_.size(); ++i) {
    double* row_i = values_.data() + offset_[i] - first_[i];  // row_i[j] = W_ij, then L_ij
    for (size_t j = first_[i]; j < i; ++j) {
      const double* row_j = values_.data() + offset_[j] - first_[j];
      double s = row_i[j];
      for (size_t k = std::max(first_[i], first_[j]); k < j; ++k) s -= row_i[k] * row_j[k];
      row_i[j] = s;
    }
    double d = row_i[i];
    for (size_t j = first_[i]; j + 1 < i; ++j) {
      const double l = row_i[j] * inverse_pivot_[j];
      d -= row_i[j] * l;
      row_i[j] = l;
    }
    if (first_[i] < i) {  // the neighbour's 1/D from a register (the critical path of a band)
      const double l = row_i[i - 1] * previous_inverse;
      d -= row_i[i - 1] * l;
      row_i[i - 1] = l;
    }
    if (!(d > 0.0)) return false;
    min_pivot = std::min(min_pivot, d);
    row_i[i] = d;
    inverse_pivot_[i] = previous_inverse = 1.0 / d;
  }
  return min_pivot > singular_below * max_diag;
}

// The neighbour's value y_{i−1} (forward) and b_{i−1}'s last update (backward) stay in a
// register: on a banded S the chain through them is the solve's critical path, and a round trip
// through memory would add to every row. Same operations in the same order as without.
void EnvelopeCholesky::solve(double* b) const {
  const size_t m = first_.size();
  if (m == 0) return;
  double previous = 0.0;
  for (size_t i = 0; i < m; ++i) {  // L y = b
    const double* row = values_.data() + offset_[i] - first_[i];
    double s = b[i];
    if (first_[i] < i) {
      for (size_t k = first_[i]; k + 1 < i; ++k) s -= row[k] * b[k];
      s -= row[i - 1] * previous;
    }
    b[i] = previous = s;
  }
  for (size_t i = 0; i < m; ++i) b[i] *= inverse_pivot_[i];  // D z = y
  double carried = b[m - 1];
  for (size_t i = m; i-- > 0;) {  // Lᵀ x = z, column by column
    const double* row = values_.data() + offset_[i] - first_[i];
    const double x = b[i] = carried;
    if (i == 0) break;
    for (size_t k = first_[i]; k + 1 < i; ++k) b[k] -= row[k] * x;
    carried = first_[i] < i ? b[i - 1] - row[i - 1] * x : b[i - 1];
  }
}

void EnvelopeCholesky::solve_rows(double* B, size_t k) const {
  const size_t m = first_.size();
  for (size_t i = 0; i < m; ++i) {  // L Y = B, a row at a time
    const double* row = values_.data() + offset_[i] - first_[i];
    double* bi = B + i * k;
    for (size_t j = first_[i]; j < i; ++j) {
      const double l = row[j];
      const double* bj = B + j * k;
      for (size_t c = 0; c < k; ++c) bi[c] -= l * bj[c];
    }
  }
  for (size_t i = 0; i < m; ++i)  // D Z = Y
    for (size_t c = 0; c < k; ++c) B[i * k + c] *= inverse_pivot_[i];
  for (size_t i = m; i-- > 0;) {  // Lᵀ X = Z
    const double* row = values_.data() + offset_[i] - first_[i];
    const double* bi = B + i * k;
    for (size_t j = first_[i]; j < i; ++j) {
      const double l = row[j];
      double* bj = B + j * k;
      for (size_t c = 0; c < k; ++c) bj[c] -= l * bi[c];
    }
  }
}

}  // namespace lagrange::dynamics
