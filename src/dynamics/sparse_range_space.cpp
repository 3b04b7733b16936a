#include "dynamics/sparse_range_space.hpp"

#include <array>
#include <cmath>
#include <map>

namespace lagrange::dynamics {

SparseRangeSpace::SparseRangeSpace(const CompiledModel& cm)
    : n_(cm.n), m_(cm.m), G_(cm.G_pattern), a0_(cm.n), lam_(cm.m) {
  // Entries of G grouped by column: S_rs = Σ_j G_rj G_sj / M_jj over shared columns j.
  std::vector<std::vector<int>> by_column(n_);
  for (size_t e = 0; e < G_.size(); ++e) by_column[G_[e].second].push_back(static_cast<int>(e));
  std::map<std::pair<int, int>, std::vector<std::array<int, 3>>> pairs;  // (r, s) → (g1, g2, j)
  for (size_t j = 0; j < n_; ++j)
    for (int e1 : by_column[j])
      for (int e2 : by_column[j]) {
        const int r = static_cast<int>(G_[static_cast<size_t>(e1)].first);
        const int s = static_cast<int>(G_[static_cast<size_t>(e2)].first);
        if (r >= s) pairs[{r, s}].push_back({e1, e2, static_cast<int>(j)});
      }
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(pairs.size() + m_);
  for (const auto& [rs, list] : pairs) triplets.emplace_back(rs.first, rs.second, 1.0);
  for (size_t r = 0; r < m_; ++r)
    triplets.emplace_back(static_cast<int>(r), static_cast<int>(r), 0.0);
  S_.resize(static_cast<long>(m_), static_cast<long>(m_));
  S_.setFromTriplets(triplets.begin(), triplets.end());  // lower triangle, duplicates summed
  S_.makeCompressed();
  for (const auto& [rs, list] : pairs) {
    const double* base = S_.valuePtr();
    const int value = static_cast<int>(&S_.coeffRef(rs.first, rs.second) - base);
    for (const auto& c : list) contributions_.push_back({value, c[0], c[1], c[2]});
  }
  llt_.analyzePattern(S_.selfadjointView<Eigen::Lower>());
}

bool SparseRangeSpace::solve(const double* m_diag, const double* g, const double* rhs,
                             const double* gamma, double* a, double* lambda) {
  for (size_t j = 0; j < n_; ++j) {
    if (!(m_diag[j] > 0.0)) return false;
    a0_[static_cast<long>(j)] = rhs[j] / m_diag[j];
  }
  double* values = S_.valuePtr();
  std::fill(values, values + S_.nonZeros(), 0.0);
  for (const auto& c : contributions_) values[c.value] += g[c.g1] * g[c.g2] / m_diag[c.column];
  llt_.factorize(S_.selfadjointView<Eigen::Lower>());
  if (llt_.info() != Eigen::Success || !well_conditioned()) return false;
  lam_.setZero();
  for (size_t e = 0; e < G_.size(); ++e)
    lam_[static_cast<long>(G_[e].first)] += g[e] * a0_[static_cast<long>(G_[e].second)];
  for (size_t r = 0; r < m_; ++r) lam_[static_cast<long>(r)] -= gamma[r];
  lam_ = llt_.solve(lam_);
  for (size_t j = 0; j < n_; ++j) a[j] = rhs[j];
  for (size_t e = 0; e < G_.size(); ++e)
    a[G_[e].second] -= g[e] * lam_[static_cast<long>(G_[e].first)];
  for (size_t j = 0; j < n_; ++j) a[j] /= m_diag[j];
  for (size_t r = 0; r < m_; ++r) lambda[r] = lam_[static_cast<long>(r)];
  return true;
}

bool SparseRangeSpace::well_conditioned() const {
  // Smallest squared pivot of the factor against the largest diagonal entry of S: a tiny
  // pivot means redundant constraints (the dense path then names them).
  const auto& L = llt_.matrixL().nestedExpression();
  double min_pivot = INFINITY, max_diag = 0.0;
  for (long k = 0; k < L.outerSize(); ++k) {
    min_pivot = std::min(min_pivot, std::abs(L.valuePtr()[L.outerIndexPtr()[k]]));
  }
  for (long k = 0; k < S_.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(S_, k); it; ++it)
      if (it.row() == it.col()) max_diag = std::max(max_diag, std::abs(it.value()));
  return min_pivot * min_pivot > 1e-13 * max_diag;
}

}  // namespace lagrange::dynamics
