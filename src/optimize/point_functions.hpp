#pragma once
// The problem's scalar functions of one collocation point (objective integrand and terminal
// term, path constraints) with their exact first derivatives, compiled onto one tape.

#include <utility>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/optimal_control.hpp"
#include "lagrange/tape.hpp"

namespace lagrange::collocation {

/// The problem's point functions in tape order: the integrand L, the terminal term Φ, the mean
/// integrand M, then the path constraints from index kFirstPath.
constexpr size_t kIntegrand = 0, kTerminal = 1, kMean = 2, kFirstPath = 3;
std::vector<GiNaC::ex> problem_functions(const OptimalControlSpec& spec);

/// Appends to `outputs` each structurally non-zero ∂f_i/∂in[columns[c]], function by function and
/// column by column, and returns their (i, c): the first derivatives every point tape carries.
std::vector<std::pair<size_t, size_t>> append_derivatives(const std::vector<GiNaC::ex>& fs,
                                                          const std::vector<GiNaC::symbol>& in,
                                                          const std::vector<size_t>& columns,
                                                          std::vector<GiNaC::ex>& outputs);

/// f_i(t, q, v, u, λ) for i < count, and their non-zero derivatives along the columns
/// (t, q₁…q_nq, v₁…v_nv, the controls, the multipliers), differentiated symbolically
/// (docs/theory.md §10).
class PointFunctions {
 public:
  /// `controls`: indices of the model inputs that are controls; `multipliers`: the symbols of λ
  /// (OptimalControlSpec::multipliers; empty for functions without them).
  PointFunctions(const Equations& eq, const CompiledModel& cm, const std::vector<GiNaC::ex>& fs,
                 const std::vector<size_t>& controls,
                 const std::vector<GiNaC::symbol>& multipliers = {});
  size_t count() const { return count_; }
  /// Values and derivatives: count() + pattern().size().
  size_t num_outputs() const { return tape_.num_outputs(); }
  /// (function, column) of each derivative, in output order.
  const std::vector<std::pair<size_t, size_t>>& pattern() const { return pattern_; }
  /// Values (count()) then derivatives (pattern()) at the tape input vector `in` (the model's
  /// layout t, q, v, u, u̇, ü, p) and the multipliers `lambda` (as many as given at construction)
  /// into `out`.
  void eval(const std::vector<double>& in, const double* lambda, std::vector<double>& out) const;

 private:
  size_t count_ = 0, multipliers_ = 0;
  mutable std::vector<double> in_;
  std::vector<std::pair<size_t, size_t>> pattern_;
  Tape tape_;
  mutable std::vector<double> work_;
};

}  // namespace lagrange::collocation
