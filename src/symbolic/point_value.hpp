#pragma once
// The value of an expression at a point (every symbol given a number), memoised over the
// expression's DAG: shared subexpressions are evaluated once, where GiNaC's subs().evalf()
// walks the tree and re-evaluates every use.

#include <ginac/ginac.h>

#include "compile/ginac_util.hpp"

namespace lagrange::symbolic {

/// Evaluates expressions at one point with GiNaC numerics (exact rationals until a function or
/// a float enters, then floats at the caller's GiNaC::Digits). One instance per point; the
/// memo is kept across calls, so expressions sharing subtrees cost their union once.
class PointValue {
 public:
  /// `at` maps every symbol the expressions contain to a numeric.
  explicit PointValue(GiNaC::exmap at) : at_(std::move(at)) {}

  /// The value of e; throws std::invalid_argument naming a symbol missing from the point.
  GiNaC::numeric operator()(const GiNaC::ex& e);

 private:
  GiNaC::numeric compute(const GiNaC::ex& e);
  GiNaC::exmap at_;
  tape_detail::ExMap<GiNaC::numeric> memo_;
};

}  // namespace lagrange::symbolic
