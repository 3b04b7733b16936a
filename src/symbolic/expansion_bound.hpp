#pragma once
// An upper bound on the size of an expansion, asked before expanding (docs/theory.md §4.1,
// "Solved accelerations"): what keeps printers from unbounded algebra.

#include <ginac/ginac.h>

#include <algorithm>
#include <cstddef>
#include <vector>

#include "compile/ginac_util.hpp"
#include "lagrange/equations.hpp"

namespace lagrange::symbolic {

/// The most terms an expansion or normal form may have that the derivation asks for on its own
/// (issue 37 item 12; docs/theory.md §4.1): beyond it, the expression is used as written.
constexpr size_t kDerivationTerms = 10000;

/// An upper bound on the number of terms of e.expand(), saturating at `cap`: a sum adds its
/// operands' bounds, a product multiplies them, a positive integer power raises to it; anything
/// else (a symbol, a function, a negative power) counts as one term. Linear in the size of e's
/// DAG (memoised), so it can be asked before an expansion that might not finish.
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
      for (GiNaC::numeric i = 0; i < k && n < cap_; ++i) n = sat_mul(n, base);
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
  tape_detail::ExMap<size_t> memo_;
};

/// True when e.expand() has at most `terms` terms by ExpansionBound.
inline bool expands_within(const GiNaC::ex& e, size_t terms) {
  return ExpansionBound(terms + 1)(e) <= terms;
}

/// True when the numerator of e.normal() has at most `terms` terms by the same bound: e's terms
/// times the product of the expansions of every distinct denominator anywhere in e (inside
/// functions too), which a common denominator multiplies into the numerator. A short sum of
/// fractions can have an exponential normal form: Σ 1/(xᵢ + yᵢ), i < 20, has 20 · 2¹⁹ terms.
inline bool normalizes_within(const GiNaC::ex& e, size_t terms) {
  ExpansionBound bound(terms + 1);
  size_t n = bound(e);
  tape_detail::ExMap<bool> seen;
  std::vector<GiNaC::ex> stack{e};
  while (!stack.empty() && n <= terms) {
    const GiNaC::ex x = stack.back();
    stack.pop_back();
    if (!seen.emplace(x, true).second) continue;
    if (GiNaC::is_a<GiNaC::power>(x) && x.op(1).info(GiNaC::info_flags::negint)) {
      const GiNaC::numeric k = -GiNaC::ex_to<GiNaC::numeric>(x.op(1));
      const size_t base = bound(x.op(0));
      for (GiNaC::numeric i = 0; i < k && n <= terms; ++i)
        n = base != 0 && n > (terms + 1) / base ? terms + 1 : std::min(terms + 1, n * base);
    }
    for (size_t i = 0; i < x.nops(); ++i) stack.push_back(x.op(i));
  }
  return n <= terms;
}

/// simplify(e) (sin² + cos² = 1 over a common denominator) when normalizes_within(e, terms),
/// else e as it is: the form printers may ask for without unbounded algebra.
inline GiNaC::ex simplify_within(const GiNaC::ex& e, size_t terms) {
  return normalizes_within(e, terms) ? simplify(e) : e;
}

}  // namespace lagrange::symbolic
