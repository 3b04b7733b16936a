#pragma once
// The gradients of the invariants C(q) = 0 and Ċ(q, v) = 0 that a collocated problem imposes at
// its start (docs/theory.md §10, "Constrained models"), compiled onto one tape: only these rows,
// not the whole dynamics' Jacobian.

#include <utility>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/tape.hpp"

namespace lagrange::collocation {

/// ∂C_k/∂q and ∂Ċ_k/∂(q, v), the structural non-zeros only, at the model's tape inputs.
class InvariantJacobian {
 public:
  InvariantJacobian(const Equations& eq, const CompiledModel& cm);
  /// (invariant, column) of each output: invariant k < m is C_k, m + k is Ċ_k; columns q, v.
  const std::vector<std::pair<size_t, size_t>>& pattern() const { return pattern_; }
  /// The gradients at the tape inputs `in` into `out` (pattern().size() values).
  void eval(const double* in, std::vector<double>& out) const;

 private:
  std::vector<std::pair<size_t, size_t>> pattern_;
  Tape tape_;
  mutable std::vector<double> work_;
};

}  // namespace lagrange::collocation
