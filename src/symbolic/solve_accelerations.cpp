// Symbolic accelerations for display: Cramer's rule with cofactor determinants, normalised only
// within a size budget (docs/theory.md §4.1, "Solved accelerations").

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include "lagrange/equations.hpp"

namespace lagrange {

namespace {

struct Hash {
  size_t operator()(const GiNaC::ex& e) const { return e.gethash(); }
};
struct Equal {
  bool operator()(const GiNaC::ex& a, const GiNaC::ex& b) const { return a.is_equal(b); }
};

// An upper bound on the number of terms of e.expand(), saturating at `cap`: a sum adds its
// operands' bounds, a product multiplies them, a positive integer power raises to it; anything
// else (a symbol, a function, a negative power) counts as one term. Linear in the size of e's
// DAG, so it can be asked before an expansion that might not finish.
class ExpansionBound {
 public:
  explicit ExpansionBound(size_t cap) : cap_(cap) {}

  size_t operator()(const GiNaC::ex& e) {
    if (const auto it = memo_.find(e); it != memo_.end()) return it->second;
    size_t n = 1;
    if (GiNaC::is_a<GiNaC::add>(e)) {
      n = 0;
      for (size_t i = 0; i < e.nops() && n < cap_; ++i) n = sat_add(n, (*this)(e.op(i)));
    } else if (GiNaC::is_a<GiNaC::mul>(e)) {
      for (size_t i = 0; i < e.nops() && n < cap_; ++i) n = sat_mul(n, (*this)(e.op(i)));
    } else if (GiNaC::is_a<GiNaC::power>(e) && e.op(1).info(GiNaC::info_flags::posint)) {
      const size_t base = (*this)(e.op(0));
      const GiNaC::numeric k = GiNaC::ex_to<GiNaC::numeric>(e.op(1));
      for (GiNaC::numeric i = 1; i < k && n < cap_; ++i) n = sat_mul(n, base);
      n = sat_mul(n, base);
    }
    memo_.emplace(e, n);
    return n;
  }

 private:
  size_t sat_add(size_t a, size_t b) const { return std::min(cap_, a + b); }
  size_t sat_mul(size_t a, size_t b) const {
    return (a != 0 && b > cap_ / a) ? cap_ : std::min(cap_, a * b);
  }
  size_t cap_;
  std::unordered_map<GiNaC::ex, size_t, Hash, Equal> memo_;
};

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
  ExpansionBound bound(budget + 1);
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
