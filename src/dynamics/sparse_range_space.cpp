#include "dynamics/sparse_range_space.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <numeric>

namespace lagrange::dynamics {

namespace {

using SmallMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0,
                                  SparseRangeSpace::kMaxBlock, SparseRangeSpace::kMaxBlock>;

// Blocks of M: the velocities joined by an off-diagonal entry (union–find), each ascending.
std::vector<std::vector<size_t>> blocks_of(size_t n, const Pattern& M) {
  std::vector<size_t> parent(n);
  std::iota(parent.begin(), parent.end(), size_t{0});
  auto root = [&](size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& [i, j] : M) parent[root(i)] = root(j);
  std::vector<std::vector<size_t>> blocks;
  std::vector<size_t> index(n, n);
  for (size_t i = 0; i < n; ++i) {
    size_t& b = index[root(i)];
    if (b == n) {
      b = blocks.size();
      blocks.emplace_back();
    }
    blocks[b].push_back(i);
  }
  return blocks;
}

std::vector<size_t> block_index(const std::vector<std::vector<size_t>>& blocks, size_t n) {
  std::vector<size_t> of(n);
  for (size_t b = 0; b < blocks.size(); ++b)
    for (size_t j : blocks[b]) of[j] = b;
  return of;
}

// Envelope of S = G M⁻¹ Gᵀ: row r reaches back to the first constraint sharing a block.
std::vector<size_t> envelope_of(size_t n, size_t m, const Pattern& M, const Pattern& G) {
  const auto blocks = blocks_of(n, M);
  const auto block_of = block_index(blocks, n);
  std::vector<size_t> first(m);
  std::iota(first.begin(), first.end(), size_t{0});
  std::vector<size_t> first_row_of_block(blocks.size(), m);
  for (const auto& [r, j] : G)
    first_row_of_block[block_of[j]] = std::min(first_row_of_block[block_of[j]], r);
  for (const auto& [r, j] : G) first[r] = std::min(first[r], first_row_of_block[block_of[j]]);
  return first;
}

// The values of a pattern grouped by row (by_row) or by column, in pattern order within a
// group: start[g] … start[g + 1] index value[] (the value's position) and other[] (its column,
// or row).
void group(const Pattern& p, size_t groups, bool by_row, std::vector<uint32_t>& start,
           std::vector<uint32_t>& value, std::vector<uint32_t>& other) {
  start.assign(groups + 1, 0);
  for (const auto& [r, c] : p) ++start[(by_row ? r : c) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  value.resize(p.size());
  other.resize(p.size());
  std::vector<uint32_t> next(start.begin(), start.end() - 1);
  for (size_t e = 0; e < p.size(); ++e) {
    const auto [r, c] = p[e];
    const uint32_t at = next[by_row ? r : c]++;
    value[at] = static_cast<uint32_t>(e);
    other[at] = static_cast<uint32_t>(by_row ? c : r);
  }
}

}  // namespace

bool SparseRangeSpace::suits(size_t n, const Pattern& M) {
  for (const auto& b : blocks_of(n, M))
    if (b.size() > kMaxBlock) return false;
  return true;
}

bool SparseRangeSpace::suits(const CompiledModel& cm) {
  return suits(cm.nv, cm.M_pattern);
}

SparseRangeSpace::SparseRangeSpace(const CompiledModel& cm)
    : SparseRangeSpace(cm.nv, cm.m, cm.M_pattern, cm.G_pattern) {}

SparseRangeSpace::SparseRangeSpace(size_t n, size_t m, const Pattern& M, const Pattern& G,
                                   double singular_below)
    : n_(n), m_(m), singular_below_(singular_below), S_(envelope_of(n, m, M, G)), a0_(n), lam_(m) {
  const auto blocks = blocks_of(n, M);
  const auto block_of = block_index(blocks, n);
  std::vector<size_t> local(n), inverse_at(blocks.size());  // inverse_at: where block b starts
  std::vector<size_t> slot(blocks.size(), blocks.size());   // block b's place in blocks_
  inverse_.assign(n, 1.0);
  std::vector<size_t> diagonal(n, M.size());
  for (size_t e = 0; e < M.size(); ++e)
    if (M[e].first == M[e].second) diagonal[M[e].first] = e;
  for (size_t b = 0; b < blocks.size(); ++b) {
    const auto& velocities = blocks[b];
    if (velocities.size() == 1) {
      const size_t j = velocities[0];
      inverse_at[b] = j;
      if (diagonal[j] == M.size()) {
        structurally_singular_ = true;
        continue;
      }
      scalar_velocity_.push_back(static_cast<uint32_t>(j));
      scalar_value_.push_back(static_cast<uint32_t>(diagonal[j]));
      continue;
    }
    Block block;
    block.offset = inverse_at[b] = inverse_.size();
    for (size_t k = 0; k < velocities.size(); ++k) {
      local[velocities[k]] = k;
      block.velocities.push_back(static_cast<uint32_t>(velocities[k]));
    }
    inverse_.resize(inverse_.size() + velocities.size() * velocities.size(), 0.0);
    slot[b] = blocks_.size();
    blocks_.push_back(std::move(block));
  }
  for (size_t e = 0; e < M.size(); ++e) {  // the larger blocks' values
    const auto [i, j] = M[e];
    const size_t b = block_of[i], k = blocks[b].size();
    if (k == 1) continue;
    auto& entries = blocks_[slot[b]].entries;
    entries.emplace_back(static_cast<uint32_t>(e), static_cast<uint32_t>(local[i] * k + local[j]));
    if (i != j)
      entries.emplace_back(static_cast<uint32_t>(e),
                           static_cast<uint32_t>(local[j] * k + local[i]));
  }
  scalars_contiguous_ = !scalar_velocity_.empty();
  for (size_t s = 0; s < scalar_velocity_.size(); ++s)
    scalars_contiguous_ = scalars_contiguous_ && scalar_velocity_[s] == scalar_velocity_[0] + s &&
                          scalar_value_[s] == scalar_value_[0] + s;
  group(G, m, true, row_start_, row_value_, row_column_);
  group(G, n, false, column_start_, column_value_, column_row_);
  // S_rs = Σ G_rj (M⁻¹)_jk G_sk over the columns j, k of one block (r ≥ s), grouped by the value
  // of S they add into, in the order of G's values within a group.
  std::vector<std::vector<uint32_t>> by_block(blocks.size());
  for (size_t e = 0; e < G.size(); ++e)
    by_block[block_of[G[e].second]].push_back(static_cast<uint32_t>(e));
  std::vector<std::pair<size_t, Contribution>> terms;
  for (size_t b = 0; b < blocks.size(); ++b)
    for (uint32_t e1 : by_block[b])
      for (uint32_t e2 : by_block[b]) {
        const auto [r, j] = G[e1];
        const auto [s, k] = G[e2];
        if (r < s) continue;
        const size_t inverse =
            blocks[b].size() == 1 ? j : inverse_at[b] + local[j] * blocks[b].size() + local[k];
        terms.push_back({S_.index(r, s), {e1, e2, static_cast<uint32_t>(inverse)}});
      }
  std::stable_sort(terms.begin(), terms.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  s_start_.assign(S_.num_values() + 1, 0);
  for (const auto& [v, c] : terms) {
    ++s_start_[v + 1];
    contributions_.push_back(c);
  }
  std::partial_sum(s_start_.begin(), s_start_.end(), s_start_.begin());
}

void SparseRangeSpace::apply_blocks(double* x) const {
  double y[kMaxBlock];
  for (const Block& b : blocks_) {
    const size_t k = b.velocities.size();
    const double* inv = inverse_.data() + b.offset;
    for (size_t i = 0; i < k; ++i) {
      y[i] = 0.0;
      for (size_t l = 0; l < k; ++l) y[i] += inv[i * k + l] * x[b.velocities[l]];
    }
    for (size_t i = 0; i < k; ++i) x[b.velocities[i]] = y[i];
  }
}

bool SparseRangeSpace::factorize(const double* m_values, const double* g) {
  // M⁻¹ block by block: 1/M_jj for a block of one velocity, a Cholesky inverse for the others.
  if (structurally_singular_) return false;
  bool positive = true;
  const size_t scalars = scalar_velocity_.size();
  if (scalars_contiguous_) {  // a run of M's values onto a run of velocities: vectorised
    const double* d = m_values + scalar_value_[0];
    double* inv = inverse_.data() + scalar_velocity_[0];
    for (size_t s = 0; s < scalars; ++s) inv[s] = 1.0 / d[s];
    for (size_t s = 0; s < scalars; ++s) positive &= d[s] > 0.0;
  } else {
    for (size_t s = 0; s < scalars; ++s) {
      const double d = m_values[scalar_value_[s]];
      positive &= d > 0.0;
      inverse_[scalar_velocity_[s]] = 1.0 / d;
    }
  }
  if (!positive) return false;
  for (const Block& b : blocks_) {
    const long k = static_cast<long>(b.velocities.size());
    double* inv = inverse_.data() + b.offset;
    std::fill(inv, inv + k * k, 0.0);
    for (const auto& [e, at] : b.entries) inv[at] = m_values[e];
    const SmallMatrix Mb = Eigen::Map<const Eigen::MatrixXd>(inv, k, k);
    const Eigen::LLT<SmallMatrix> llt(Mb);
    if (llt.info() != Eigen::Success) return false;
    const SmallMatrix Minv = llt.solve(SmallMatrix::Identity(k, k));
    Eigen::Map<Eigen::MatrixXd>(inv, k, k) = Minv;  // symmetric: row- or column-major alike
  }
  double* values = S_.values();
  for (size_t v = 0; v + 1 < s_start_.size(); ++v) {
    double s = 0.0;
    for (uint32_t c = s_start_[v]; c < s_start_[v + 1]; ++c) {
      const Contribution& t = contributions_[c];
      s += g[t.g1] * inverse_[t.inverse] * g[t.g2];
    }
    values[v] = s;
  }
  return S_.factorize(singular_below_);
}

void SparseRangeSpace::solve_factored(const double* g, const double* rhs, const double* gamma,
                                      double* a, double* lambda) {
  double* a0 = a0_.data();
  for (size_t j = 0; j < n_; ++j) a0[j] = rhs[j] * inverse_[j];
  apply_blocks(a0);
  for (size_t r = 0; r < m_; ++r) {  // G a₀ − γ
    double s = 0.0;
    for (uint32_t e = row_start_[r]; e < row_start_[r + 1]; ++e)
      s += g[row_value_[e]] * a0[row_column_[e]];
    lam_[r] = s - gamma[r];
  }
  S_.solve(lam_.data());
  for (size_t j = 0; j < n_; ++j) {  // M⁻¹(h + Q − Gᵀλ)
    double s = rhs[j];
    for (uint32_t e = column_start_[j]; e < column_start_[j + 1]; ++e)
      s -= g[column_value_[e]] * lam_[column_row_[e]];
    a[j] = s * inverse_[j];
  }
  apply_blocks(a);
  std::copy(lam_.begin(), lam_.end(), lambda);
}

void SparseRangeSpace::apply_inverse_rows(double* X, size_t k) const {
  for (size_t j = 0; j < n_; ++j)
    for (size_t c = 0; c < k; ++c) X[j * k + c] *= inverse_[j];
  std::vector<double> y;
  for (const Block& b : blocks_) {
    const size_t s = b.velocities.size();
    const double* inv = inverse_.data() + b.offset;
    y.assign(s * k, 0.0);
    for (size_t i = 0; i < s; ++i)
      for (size_t l = 0; l < s; ++l) {
        const double w = inv[i * s + l];
        const double* x = X + b.velocities[l] * k;
        for (size_t c = 0; c < k; ++c) y[i * k + c] += w * x[c];
      }
    for (size_t i = 0; i < s; ++i)
      std::copy(y.begin() + static_cast<long>(i * k), y.begin() + static_cast<long>((i + 1) * k),
                X + b.velocities[i] * k);
  }
}

void SparseRangeSpace::solve_factored(const double* g, size_t k, const double* rhs,
                                      const double* gamma, double* a) const {
  // S Λ = G M⁻¹ R₁ − Γ, A = M⁻¹(R₁ − Gᵀ Λ), as solve_factored above, a row of k at a time.
  std::vector<double> a0(rhs, rhs + n_ * k), lam(gamma, gamma + m_ * k);
  apply_inverse_rows(a0.data(), k);
  for (double& x : lam) x = -x;
  for (size_t r = 0; r < m_; ++r)
    for (uint32_t e = row_start_[r]; e < row_start_[r + 1]; ++e) {
      const double w = g[row_value_[e]];
      const double* x = a0.data() + row_column_[e] * k;
      double* l = lam.data() + r * k;
      for (size_t c = 0; c < k; ++c) l[c] += w * x[c];
    }
  S_.solve_rows(lam.data(), k);
  std::copy(rhs, rhs + n_ * k, a);
  for (size_t j = 0; j < n_; ++j)
    for (uint32_t e = column_start_[j]; e < column_start_[j + 1]; ++e) {
      const double w = g[column_value_[e]];
      const double* l = lam.data() + column_row_[e] * k;
      double* x = a + j * k;
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
