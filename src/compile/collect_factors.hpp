#pragma once
// GiNaC-level rewrite Σᵢ cᵢ·aᵢ·X → X·(Σᵢ cᵢ·aᵢ) applied before a tape is emitted (docs/theory.md
// §8).

#include <ginac/ginac.h>

#include <vector>

#include "compile/canonical_order.hpp"

namespace lagrange {

/// Pulls common factors out of every sum in `e`: terms cᵢ·aᵢ·X whose remainder X (after
/// removing one plain symbol factor aᵢ) is the same expression become X·(Σ cᵢ·aᵢ); ties
/// are broken in canonical order (compile/canonical_order.hpp), never in GiNaC's. Sums
/// anywhere in the DAG are rewritten bottom-up, each distinct subexpression once; the cost is
/// linear in the number of terms times the square of their factor count (no expand/collect).
/// Unlike GiNaC::collect_common_factors (found by argument-dependent lookup, so qualify the
/// call), it never computes polynomial gcds.
GiNaC::ex collect_common_factors(const GiNaC::ex& e);

/// collect_common_factors over several expressions, sharing the work on common subexpressions;
/// where several rewrites are equally good, the first in `order` is taken.
std::vector<GiNaC::ex> collect_common_factors(const std::vector<GiNaC::ex>& es,
                                              tape_detail::CanonicalOrder& order);

}  // namespace lagrange
