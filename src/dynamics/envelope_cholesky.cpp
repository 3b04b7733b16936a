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
}

// Row-oriented envelope Cholesky: L_ij = (A_ij − Σ_k L_ik L_jk) / L_jj over the overlap of
// the two rows' envelopes, L_ii = √(A_ii − Σ_k L_ik²).
bool EnvelopeCholesky::factorize() {
  double max_diag = 0.0, min_pivot2 = INFINITY;
  for (size_t i = 0; i < first_.size(); ++i)
    max_diag = std::max(max_diag, std::abs(values_[index(i, i)]));
  for (size_t i = 0; i < first_.size(); ++i) {
    double* row_i = values_.data() + offset_[i] - first_[i];  // row_i[j] = L_ij
    for (size_t j = first_[i]; j <= i; ++j) {
      const double* row_j = values_.data() + offset_[j] - first_[j];
      double s = row_i[j];
      for (size_t k = std::max(first_[i], first_[j]); k < j; ++k) s -= row_i[k] * row_j[k];
      if (j < i) {
        row_i[j] = s / row_j[j];
      } else {
        if (!(s > 0.0)) return false;
        min_pivot2 = std::min(min_pivot2, s);
        row_i[i] = std::sqrt(s);
      }
    }
  }
  return min_pivot2 > 1e-13 * max_diag;
}

void EnvelopeCholesky::solve(double* b) const {
  const size_t m = first_.size();
  for (size_t i = 0; i < m; ++i) {  // L y = b
    const double* row = values_.data() + offset_[i] - first_[i];
    double s = b[i];
    for (size_t k = first_[i]; k < i; ++k) s -= row[k] * b[k];
    b[i] = s / row[i];
  }
  for (size_t i = m; i-- > 0;) {  // Lᵀ x = y, column by column
    const double* row = values_.data() + offset_[i] - first_[i];
    b[i] /= row[i];
    for (size_t k = first_[i]; k < i; ++k) b[k] -= row[k] * b[i];
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
    const double inv = 1.0 / row[i];
    for (size_t c = 0; c < k; ++c) bi[c] *= inv;
  }
  for (size_t i = m; i-- > 0;) {  // Lᵀ X = Y
    const double* row = values_.data() + offset_[i] - first_[i];
    double* bi = B + i * k;
    const double inv = 1.0 / row[i];
    for (size_t c = 0; c < k; ++c) bi[c] *= inv;
    for (size_t j = first_[i]; j < i; ++j) {
      const double l = row[j];
      double* bj = B + j * k;
      for (size_t c = 0; c < k; ++c) bj[c] -= l * bi[c];
    }
  }
}

}  // namespace lagrange::dynamics
