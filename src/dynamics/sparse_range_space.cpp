#include "dynamics/sparse_range_space.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <numeric>

namespace lagrange::dynamics {

namespace {

// Blocks of M: the velocities joined by an off-diagonal entry (union–find), each ascending.
std::vector<std::vector<size_t>> blocks_of(const CompiledModel& cm) {
  std::vector<size_t> parent(cm.nv);
  std::iota(parent.begin(), parent.end(), size_t{0});
  auto root = [&](size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& [i, j] : cm.M_pattern) parent[root(i)] = root(j);
  std::vector<std::vector<size_t>> blocks;
  std::vector<size_t> index(cm.nv, cm.nv);
  for (size_t i = 0; i < cm.nv; ++i) {
    size_t& b = index[root(i)];
    if (b == cm.nv) {
      b = blocks.size();
      blocks.emplace_back();
    }
    blocks[b].push_back(i);
  }
  return blocks;
}

// Envelope of S = G M⁻¹ Gᵀ: row r reaches back to the first constraint sharing a block.
std::vector<size_t> envelope_of(const CompiledModel& cm, const std::vector<size_t>& block_of,
                                size_t blocks) {
  std::vector<size_t> first(cm.m);
  for (size_t r = 0; r < cm.m; ++r) first[r] = r;
  std::vector<size_t> first_row_of_block(blocks, cm.m);
  for (const auto& [r, j] : cm.G_pattern)
    first_row_of_block[block_of[j]] = std::min(first_row_of_block[block_of[j]], r);
  for (const auto& [r, j] : cm.G_pattern)
    first[r] = std::min(first[r], first_row_of_block[block_of[j]]);
  return first;
}

std::vector<size_t> block_index(const std::vector<std::vector<size_t>>& blocks, size_t n) {
  std::vector<size_t> of(n);
  for (size_t b = 0; b < blocks.size(); ++b)
    for (size_t j : blocks[b]) of[j] = b;
  return of;
}

}  // namespace

bool SparseRangeSpace::suits(const CompiledModel& cm) {
  for (const auto& b : blocks_of(cm))
    if (b.size() > kMaxBlock) return false;
  return true;
}

SparseRangeSpace::SparseRangeSpace(const CompiledModel& cm)
    : n_(cm.nv),
      m_(cm.m),
      M_(cm.M_pattern),
      G_(cm.G_pattern),
      blocks_(blocks_of(cm)),
      block_of_(block_index(blocks_, cm.nv)),
      local_(cm.nv),
      S_(envelope_of(cm, block_of_, blocks_.size())),
      a0_(cm.nv),
      lam_(cm.m) {
  size_t size = 0;
  for (const auto& b : blocks_) {
    offset_.push_back(size);
    for (size_t k = 0; k < b.size(); ++k) local_[b[k]] = k;
    size += b.size() * b.size();
  }
  inverse_.assign(size, 0.0);
  scratch_.assign(kMaxBlock, 0.0);
  // S_rs = Σ G_rj (M⁻¹)_jk G_sk over the columns j, k of one block (r ≥ s).
  std::vector<std::vector<int>> by_block(blocks_.size());
  for (size_t e = 0; e < G_.size(); ++e)
    by_block[block_of_[G_[e].second]].push_back(static_cast<int>(e));
  for (size_t b = 0; b < blocks_.size(); ++b)
    for (int e1 : by_block[b])
      for (int e2 : by_block[b]) {
        const auto& [r, j] = G_[static_cast<size_t>(e1)];
        const auto& [s, k] = G_[static_cast<size_t>(e2)];
        if (r >= s)
          contributions_.push_back(
              {S_.index(r, s), e1, e2, offset_[b] + local_[j] * blocks_[b].size() + local_[k]});
      }
}

void SparseRangeSpace::apply_inverse(double* x) {
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const auto& cols = blocks_[b];
    const size_t k = cols.size();
    const double* inv = inverse_.data() + offset_[b];
    double* y = scratch_.data();
    for (size_t i = 0; i < k; ++i) {
      y[i] = 0.0;
      for (size_t l = 0; l < k; ++l) y[i] += inv[i * k + l] * x[cols[l]];
    }
    for (size_t i = 0; i < k; ++i) x[cols[i]] = y[i];
  }
}

bool SparseRangeSpace::factorize(const double* m_values, const double* g) {
  // M⁻¹ block by block (a block of one velocity is 1/M_jj).
  std::fill(inverse_.begin(), inverse_.end(), 0.0);
  for (size_t e = 0; e < M_.size(); ++e) {
    const auto& [i, j] = M_[e];
    const size_t b = block_of_[i], k = blocks_[b].size();
    double* inv = inverse_.data() + offset_[b];
    inv[local_[i] * k + local_[j]] = inv[local_[j] * k + local_[i]] = m_values[e];
  }
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const long k = static_cast<long>(blocks_[b].size());
    double* inv = inverse_.data() + offset_[b];
    if (k == 1) {
      if (!(inv[0] > 0.0)) return false;
      inv[0] = 1.0 / inv[0];
      continue;
    }
    const Block Mb = Eigen::Map<const Eigen::MatrixXd>(inv, k, k);
    const Eigen::LLT<Block> llt(Mb);
    if (llt.info() != Eigen::Success) return false;
    const Block Minv = llt.solve(Block::Identity(k, k));
    Eigen::Map<Eigen::MatrixXd>(inv, k, k) = Minv;  // symmetric: row- or column-major alike
  }
  double* values = S_.values();
  std::fill(values, values + S_.num_values(), 0.0);
  for (const auto& c : contributions_) values[c.value] += g[c.g1] * inverse_[c.inverse] * g[c.g2];
  return S_.factorize();
}

void SparseRangeSpace::solve_factored(const double* g, const double* rhs, const double* gamma,
                                      double* a, double* lambda) {
  for (size_t j = 0; j < n_; ++j) a0_[static_cast<long>(j)] = rhs[j];
  apply_inverse(a0_.data());
  lam_.setZero();
  for (size_t e = 0; e < G_.size(); ++e)
    lam_[static_cast<long>(G_[e].first)] += g[e] * a0_[static_cast<long>(G_[e].second)];
  for (size_t r = 0; r < m_; ++r) lam_[static_cast<long>(r)] -= gamma[r];
  S_.solve(lam_.data());
  for (size_t j = 0; j < n_; ++j) a[j] = rhs[j];
  for (size_t e = 0; e < G_.size(); ++e)
    a[G_[e].second] -= g[e] * lam_[static_cast<long>(G_[e].first)];
  apply_inverse(a);
  for (size_t r = 0; r < m_; ++r) lambda[r] = lam_[static_cast<long>(r)];
}

void SparseRangeSpace::apply_inverse_rows(double* X, size_t k) const {
  std::vector<double> y;
  for (size_t b = 0; b < blocks_.size(); ++b) {
    const auto& cols = blocks_[b];
    const size_t s = cols.size();
    const double* inv = inverse_.data() + offset_[b];
    if (s == 1) {
      double* x = X + cols[0] * k;
      for (size_t c = 0; c < k; ++c) x[c] *= inv[0];
      continue;
    }
    y.assign(s * k, 0.0);
    for (size_t i = 0; i < s; ++i)
      for (size_t l = 0; l < s; ++l) {
        const double w = inv[i * s + l];
        const double* x = X + cols[l] * k;
        for (size_t c = 0; c < k; ++c) y[i * k + c] += w * x[c];
      }
    for (size_t i = 0; i < s; ++i)
      std::copy(y.begin() + static_cast<long>(i * k), y.begin() + static_cast<long>((i + 1) * k),
                X + cols[i] * k);
  }
}

void SparseRangeSpace::solve_factored(const double* g, size_t k, const double* rhs,
                                      const double* gamma, double* a) const {
  // S Λ = G M⁻¹ R₁ − Γ, A = M⁻¹(R₁ − Gᵀ Λ), as solve_factored above, a row of k at a time.
  std::vector<double> a0(rhs, rhs + n_ * k), lam(gamma, gamma + m_ * k);
  apply_inverse_rows(a0.data(), k);
  for (double& x : lam) x = -x;
  for (size_t e = 0; e < G_.size(); ++e) {
    const double w = g[e];
    const double* x = a0.data() + G_[e].second * k;
    double* l = lam.data() + G_[e].first * k;
    for (size_t c = 0; c < k; ++c) l[c] += w * x[c];
  }
  S_.solve_rows(lam.data(), k);
  std::copy(rhs, rhs + n_ * k, a);
  for (size_t e = 0; e < G_.size(); ++e) {
    const double w = g[e];
    const double* l = lam.data() + G_[e].first * k;
    double* x = a + G_[e].second * k;
    for (size_t c = 0; c < k; ++c) x[c] -= w * l[c];
  }
  apply_inverse_rows(a, k);
}

bool SparseRangeSpace::solve(const double* m_values, const double* g, const double* rhs,
                             const double* gamma, double* a, double* lambda) {
  if (!factorize(m_values, g)) return false;
  solve_factored(g, rhs, gamma, a, lambda);
  return true;
}

}  // namespace lagrange::dynamics
