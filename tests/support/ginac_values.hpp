#pragma once
// Comparing and evaluating GiNaC expressions in tests.

#include <ginac/ginac.h>

namespace lagrange {

/// Whether x and y are the same expression (their difference expands and normalises to 0).
inline bool same(const GiNaC::ex& x, const GiNaC::ex& y) {
  return (x - y).expand().normal().is_zero();
}

/// The number e takes with the substitutions `at`.
inline double value(const GiNaC::ex& e, const GiNaC::exmap& at) {
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(at).evalf()).to_double();
}

}  // namespace lagrange
