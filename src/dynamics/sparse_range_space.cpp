#include "dynamics/sparse_range_space.hpp"

#include <algorithm>

namespace lagrange::dynamics {

namespace {

// Envelope of S = G M⁻¹ Gᵀ: row r reaches back to the first constraint sharing a column.
std::vector<size_t> envelope_of(const CompiledModel& cm) {
  std::vector<size_t> first(cm.m);
  for (size_t r = 0; r < cm.m; ++r) first[r] = r;
  std::vector<size_t> first_row_of_column(cm.nv, cm.m);
  for (const auto& [r, j] : cm.G_pattern)
    first_row_of_column[j] = std::min(first_row_of_column[j], r);
  for (const auto& [r, j] : cm.G_pattern) first[r] = std::min(first[r], first_row_of_column[j]);
  return first;
}

}  // namespace

SparseRangeSpace::SparseRangeSpace(const CompiledModel& cm)
    : n_(cm.nv), m_(cm.m), G_(cm.G_pattern), S_(envelope_of(cm)), a0_(cm.nv), lam_(cm.m) {
  // S_rs = Σ_j G_rj G_sj / M_jj over the columns j the two constraints share (r ≥ s).
  std::vector<std::vector<int>> by_column(n_);
  for (size_t e = 0; e < G_.size(); ++e) by_column[G_[e].second].push_back(static_cast<int>(e));
  for (size_t j = 0; j < n_; ++j)
    for (int e1 : by_column[j])
      for (int e2 : by_column[j]) {
        const size_t r = G_[static_cast<size_t>(e1)].first, s = G_[static_cast<size_t>(e2)].first;
        if (r >= s) contributions_.push_back({S_.index(r, s), e1, e2, static_cast<int>(j)});
      }
}

bool SparseRangeSpace::solve(const double* m_diag, const double* g, const double* rhs,
                             const double* gamma, double* a, double* lambda) {
  for (size_t j = 0; j < n_; ++j) {
    if (!(m_diag[j] > 0.0)) return false;
    a0_[static_cast<long>(j)] = rhs[j] / m_diag[j];
  }
  double* values = S_.values();
  std::fill(values, values + S_.num_values(), 0.0);
  for (const auto& c : contributions_) values[c.value] += g[c.g1] * g[c.g2] / m_diag[c.column];
  if (!S_.factorize()) return false;
  lam_.setZero();
  for (size_t e = 0; e < G_.size(); ++e)
    lam_[static_cast<long>(G_[e].first)] += g[e] * a0_[static_cast<long>(G_[e].second)];
  for (size_t r = 0; r < m_; ++r) lam_[static_cast<long>(r)] -= gamma[r];
  S_.solve(lam_.data());
  for (size_t j = 0; j < n_; ++j) a[j] = rhs[j];
  for (size_t e = 0; e < G_.size(); ++e)
    a[G_[e].second] -= g[e] * lam_[static_cast<long>(G_[e].first)];
  for (size_t j = 0; j < n_; ++j) a[j] /= m_diag[j];
  for (size_t r = 0; r < m_; ++r) lambda[r] = lam_[static_cast<long>(r)];
  return true;
}

}  // namespace lagrange::dynamics
