#pragma once
// Small helpers over GiNaC: structural hashing of ex and read access to add/mul pairs.

#include <ginac/ginac.h>

#include <unordered_map>

namespace lagrange::tape_detail {

/// Hash of an expression's structure (GiNaC caches it in the node).
struct ExHash {
  size_t operator()(const GiNaC::ex& e) const { return e.gethash(); }
};

/// Structural equality (pointer-equal subtrees compare in O(1)).
struct ExEqual {
  bool operator()(const GiNaC::ex& a, const GiNaC::ex& b) const { return a.is_equal(b); }
};

/// A map keyed on expression structure.
template <class T>
using ExMap = std::unordered_map<GiNaC::ex, T, ExHash, ExEqual>;

/// Read access to the (rest, coeff) pairs and overall coefficient of an add or mul, without
/// GiNaC's op(i), which allocates a recombined rest·coeff (add) or rest^coeff (mul) per call.
struct PairAccess : GiNaC::expairseq {
  /// The pairs: for add, term = rest·coeff; for mul, factor = rest^coeff.
  static const GiNaC::epvector& pairs(const GiNaC::expairseq& e) { return e.*(&PairAccess::seq); }
  /// The numeric constant term (add) or leading coefficient (mul).
  static const GiNaC::ex& overall(const GiNaC::expairseq& e) {
    return e.*(&PairAccess::overall_coeff);
  }
};

}  // namespace lagrange::tape_detail
