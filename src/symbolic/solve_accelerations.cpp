// Symbolic accelerations for display: Cramer's rule with cofactor determinants, normalised only
// within a size budget (docs/theory.md §4.1, "Solved accelerations").

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "lagrange/equations.hpp"
#include "symbolic/expansion_bound.hpp"

namespace lagrange {

namespace {

// The determinant of the n × n matrix m (n ≤ 4) by cofactor expansion along the first row,
// unexpanded and unnormalised: at most 24 products, whatever the entries.
GiNaC::ex cofactor_determinant(const GiNaC::matrix& m) {
  const unsigned n = m.rows();
  if (n == 1) return m(0, 0);
  GiNaC::ex det = 0;
  for (unsigned c = 0; c < n; ++c) {
    if (m(0, c).is_zero()) continue;
    GiNaC::matrix minor(n - 1, n - 1);
    for (unsigned r = 1; r < n; ++r)
      for (unsigned k = 0, kk = 0; k < n; ++k)
        if (k != c) minor(r - 1, kk++) = m(r, k);
    det += (c % 2 == 0 ? 1 : -1) * m(0, c) * cofactor_determinant(minor);
  }
  return det;
}

}  // namespace

// docs/theory.md §4.1, "Solved accelerations": a_i = det(M_i)/det(M), M_i being M with column i
// replaced by h + Q; each quotient is simplified (normal form, sin² + cos² = 1) only when the
// expansions of its numerator and denominator are bounded by `budget` terms.
std::optional<std::vector<GiNaC::ex>> solve_accelerations(const Equations& eq, size_t budget) {
  if (eq.m > 0) throw std::invalid_argument("solve_accelerations: the system is constrained");
  if (eq.nv > 4) throw std::invalid_argument("solve_accelerations: more than 4 coordinates");
  const unsigned n = static_cast<unsigned>(eq.nv);
  symbolic::ExpansionBound bound(budget + 1);
  const GiNaC::ex den = cofactor_determinant(eq.M);
  if (bound(den) > budget) return std::nullopt;
  std::vector<GiNaC::ex> out;
  for (unsigned i = 0; i < n; ++i) {
    GiNaC::matrix Mi = eq.M;
    for (unsigned r = 0; r < n; ++r) Mi(r, i) = eq.h[r] + eq.Q[r];
    const GiNaC::ex num = cofactor_determinant(Mi);
    if (bound(num) > budget) return std::nullopt;
    out.push_back(simplify(num / den));
  }
  return out;
}

std::vector<GiNaC::ex> solve_accelerations(const Equations& eq) {
  return *solve_accelerations(eq, std::numeric_limits<size_t>::max() - 1);
}

}  // namespace lagrange
