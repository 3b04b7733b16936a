// The exact Newton matrix of the index-1 DAE that IDA integrates (include/lagrange/analysis.hpp,
// dae_jacobian).

#include <fmt/format.h>

#include <algorithm>
#include <random>
#include <stdexcept>

#include "analysis/off_kink.hpp"
#include "lagrange/analysis.hpp"

namespace lagrange {

namespace {

/// Where one non-zero of the implicit form's matrices goes in the Newton matrix, and by what
/// factor: ±1, or c_j (∂F/∂v' = [M; G], and the identity ∂F_q/∂q').
struct Term {
  enum class From : unsigned char { qdot_x, Phi_x, K, one } from;
  size_t source;  ///< index into that matrix's values (unused for `one`)
  size_t dest;    ///< index into the Newton matrix's values
  double sign;
  bool times_cj;
};

}  // namespace

// docs/theory.md §5.6, "The DAE's Newton matrix": with y = (q, v, λ) and
// F = (q' − q̇(q, v), Φ(q, v, v', λ)),
//   ∂F/∂y + c_j ∂F/∂y' = [ c_j 1 − ∂q̇/∂q   −∂q̇/∂v          0       ]
//                        [ Φ_q             Φ_v + c_j [M; G]  [Gᵀ; 0] ].
DaeJacobian dae_jacobian(const DynamicsJacobian& jac, Dynamics& dyn, double t0,
                         const std::vector<double>& y0) {
  const CompiledModel& cm = jac.model();
  const long nq = static_cast<long>(cm.nq), nv = static_cast<long>(cm.nv);
  const long m = static_cast<long>(cm.m), n = nq + nv, size = n + m;
  if (y0.size() < static_cast<size_t>(n))
    throw std::invalid_argument(
        fmt::format("dae_jacobian: expected a state of at least {} values, got {}", n, y0.size()));
  // The patterns are the layout's, whatever the state: take them at the start.
  const std::vector<double> zeros(static_cast<size_t>(nv + m), 0.0);
  const ImplicitJacobian P =
      jac.implicit(dyn, t0, y0.data(), y0.data() + nq, zeros.data(), zeros.data() + nv);

  std::vector<Term> terms;
  std::vector<std::pair<long, long>> where;
  const auto add = [&](Term::From from, size_t source, long row, long col, double sign, bool cj) {
    terms.push_back({from, source, 0, sign, cj});
    where.emplace_back(row, col);
  };
  const auto each = [](const Eigen::SparseMatrix<double>& A, auto&& f) {
    for (long c = 0; c < A.outerSize(); ++c)
      for (long e = A.outerIndexPtr()[c]; e < A.outerIndexPtr()[c + 1]; ++e)
        f(static_cast<size_t>(e), static_cast<long>(A.innerIndexPtr()[e]), c);
  };
  for (long i = 0; i < nq; ++i) add(Term::From::one, 0, i, i, 1.0, true);
  each(P.qdot_x, [&](size_t e, long r, long c) { add(Term::From::qdot_x, e, r, c, -1.0, false); });
  each(P.Phi_x, [&](size_t e, long r, long c) {
    if (c < n) add(Term::From::Phi_x, e, nq + r, c, 1.0, false);  // not the inputs' columns
  });
  each(P.K, [&](size_t e, long r, long c) {
    if (c < nv)
      add(Term::From::K, e, nq + r, nq + c, 1.0, true);  // ∂Φ/∂v' = ∂Φ/∂a
    else
      add(Term::From::K, e, nq + r, c + nq, 1.0, false);  // ∂Φ/∂λ
  });

  // The union pattern in compressed columns, rows ascending, and each term's place in it.
  std::vector<std::vector<long>> column(static_cast<size_t>(size));
  for (const auto& [r, c] : where) column[static_cast<size_t>(c)].push_back(r);
  DaeJacobian out;
  out.column_starts.push_back(0);
  for (auto& rows : column) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
    out.rows.insert(out.rows.end(), rows.begin(), rows.end());
    out.column_starts.push_back(static_cast<long>(out.rows.size()));
  }
  for (size_t k = 0; k < terms.size(); ++k) {
    const auto [r, c] = where[k];
    const auto first = out.rows.begin() + out.column_starts[static_cast<size_t>(c)];
    const auto last = out.rows.begin() + out.column_starts[static_cast<size_t>(c) + 1];
    terms[k].dest = static_cast<size_t>(std::lower_bound(first, last, r) - out.rows.begin());
  }

  const size_t nonzeros = out.rows.size();
  out.values = [&jac, &dyn, terms = std::move(terms), nq, n, nonzeros](
                   double t, double cj, const double* y, const double* yp, double* values) {
    // v' is the accelerations a of the implicit form, y's λ its multipliers.
    const ImplicitJacobian J = analysis_detail::implicit_off_kink(jac, dyn, t, y, yp + nq, y + n);
    std::fill(values, values + nonzeros, 0.0);
    for (const Term& term : terms) {
      double x = term.sign * (term.times_cj ? cj : 1.0);
      switch (term.from) {
        case Term::From::qdot_x:
          x *= J.qdot_x.valuePtr()[term.source];
          break;
        case Term::From::Phi_x:
          x *= J.Phi_x.valuePtr()[term.source];
          break;
        case Term::From::K:
          x *= J.K.valuePtr()[term.source];
          break;
        case Term::From::one:
          break;
      }
      values[term.dest] += x;
    }
  };
  return out;
}

}  // namespace lagrange
