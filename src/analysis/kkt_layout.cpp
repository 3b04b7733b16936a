// The implicit form's sparse matrices from the Jacobian tape (docs/theory.md §5.1).

#include "analysis/kkt_layout.hpp"

#include <algorithm>

namespace lagrange::analysis_detail {

void KktLayout::Scatter::finish(long rows, long cols,
                                const std::vector<std::pair<long, long>>& where) {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(where.size());
  for (const auto& [r, c] : where) entries.emplace_back(r, c, 1.0);
  pattern.resize(rows, cols);
  pattern.setFromTriplets(entries.begin(), entries.end());
  pattern.makeCompressed();
  const int* outer = pattern.outerIndexPtr();
  const int* inner = pattern.innerIndexPtr();
  for (size_t e = 0; e < terms.size(); ++e) {
    const auto [r, c] = where[e];
    const int* hit = std::lower_bound(inner + outer[c], inner + outer[c + 1], static_cast<int>(r));
    terms[e].dest = static_cast<size_t>(hit - inner);
  }
}

void KktLayout::Scatter::fill(const double* out, const double* a, const double* lambda,
                              double alpha, Eigen::SparseMatrix<double>& into) const {
  into = pattern;
  double* values = into.valuePtr();
  std::fill(values, values + into.nonZeros(), 0.0);
  for (const Term& t : terms) {
    double f = 1.0;
    switch (t.factor) {
      case Factor::one:
        break;
      case Factor::minus_one:
        f = -1.0;
        break;
      case Factor::a:
        f = a[t.index];
        break;
      case Factor::lambda:
        f = lambda[t.index];
        break;
      case Factor::two_alpha:
        f = 2.0 * alpha;
        break;
      case Factor::alpha_squared:
        f = alpha * alpha;
        break;
    }
    values[t.dest] += f * out[t.source];
  }
}

// docs/theory.md §5.1: Φ = (M a + Gᵀλ − f, G a + c + 2αĊ + α²C), so along a column x
// ∂Φ/∂x = (M′a + G′ᵀλ − f′, G′a + c′ + 2αĊ′ + α²C′) with a and λ held.
KktLayout::KktLayout(const CompiledModel& cm, const std::vector<std::pair<size_t, size_t>>& pattern,
                     size_t values, size_t columns) {
  const long n = static_cast<long>(cm.nv), m = static_cast<long>(cm.m);
  const long nq = static_cast<long>(cm.nq);
  std::vector<std::pair<long, long>> k_at, phi_at, qdot_at;
  const auto k_term = [&](size_t source, long r, long c) {
    K_.terms.push_back({source, 0, Factor::one, 0});
    k_at.emplace_back(r, c);
  };
  for (size_t e = 0; e < cm.M_pattern.size(); ++e) {
    const long i = static_cast<long>(cm.M_pattern[e].first);
    const long j = static_cast<long>(cm.M_pattern[e].second);
    k_term(e, i, j);
    if (i != j) k_term(e, j, i);
  }
  for (size_t e = 0; e < cm.G_pattern.size(); ++e) {
    const long r = static_cast<long>(cm.G_pattern[e].first);
    const long j = static_cast<long>(cm.G_pattern[e].second);
    k_term(cm.G_out() + e, n + r, j);
    k_term(cm.G_out() + e, j, n + r);
  }
  K_.finish(n + m, n + m, k_at);

  const auto phi_term = [&](size_t source, long r, long c, Factor f, size_t index = 0) {
    Phi_.terms.push_back({source, 0, f, index});
    phi_at.emplace_back(r, c);
  };
  for (size_t e = 0; e < pattern.size(); ++e) {
    const size_t r = pattern[e].first, source = values + e;
    const long k = static_cast<long>(pattern[e].second);
    if (r < cm.rhs_out()) {  // M′a
      const size_t i = cm.M_pattern[r].first, j = cm.M_pattern[r].second;
      phi_term(source, static_cast<long>(i), k, Factor::a, j);
      if (i != j) phi_term(source, static_cast<long>(j), k, Factor::a, i);
    } else if (r < cm.qdot_out()) {  // −f′
      phi_term(source, static_cast<long>(r - cm.rhs_out()), k, Factor::minus_one);
    } else if (r < cm.G_out()) {  // q̇′
      if (k >= nq + n) continue;
      qdot_.terms.push_back({source, 0, Factor::one, 0});
      qdot_at.emplace_back(static_cast<long>(r - cm.qdot_out()), k);
    } else if (r < cm.c_out()) {  // G′ᵀλ and G′a
      const size_t row = cm.G_pattern[r - cm.G_out()].first;
      const size_t j = cm.G_pattern[r - cm.G_out()].second;
      phi_term(source, static_cast<long>(j), k, Factor::lambda, row);
      phi_term(source, n + static_cast<long>(row), k, Factor::a, j);
    } else if (r < cm.Cdot_out()) {  // c′
      phi_term(source, n + static_cast<long>(r - cm.c_out()), k, Factor::one);
    } else if (r < cm.C_out()) {  // 2αĊ′
      phi_term(source, n + static_cast<long>(r - cm.Cdot_out()), k, Factor::two_alpha);
    } else if (r < cm.Cq_out()) {  // α²C′
      phi_term(source, n + static_cast<long>(r - cm.C_out()), k, Factor::alpha_squared);
    }
  }
  Phi_.finish(n + m, static_cast<long>(columns), phi_at);
  qdot_.finish(nq, nq + n, qdot_at);
}

void KktLayout::assemble(const double* out, const double* a, const double* lambda, double alpha,
                         ImplicitJacobian& J) const {
  K_.fill(out, a, lambda, alpha, J.K);
  Phi_.fill(out, a, lambda, alpha, J.Phi_x);
  qdot_.fill(out, a, lambda, alpha, J.qdot_x);
}

}  // namespace lagrange::analysis_detail
