#pragma once
// The index-1 DAE's residual at one collocation point, without its linear q' term, as
// expressions of the tape inputs, a = v', λ and α, and compiled with its exact first derivatives
// onto one tape: the Jacobian's rows of the dynamics in one evaluation (docs/theory.md §10).

#include <ginac/ginac.h>

#include <string>
#include <utility>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "optimize/machine_tape.hpp"

namespace lagrange::collocation {

/// New symbols name0, name1, … (count of them).
std::vector<GiNaC::symbol> numbered_symbols(const std::string& name, size_t count);

/// The symbols the residual adds to the model's tape inputs: a (nv), λ (m) and α, in that order.
struct ResidualSymbols {
  std::vector<GiNaC::symbol> a, lambda;
  GiNaC::symbol alpha;
  ResidualSymbols(size_t nv, size_t m);
};

/// ρ = (−q̇(q, v), M a + Gᵀλ − (h + Q), G a + c + 2αĊ + α²C) (docs/theory.md §4.3, §10): the
/// residual r = ρ + (q', 0, 0), nq + nv + m rows.
std::vector<GiNaC::ex> residual_rows(const Equations& eq, const CompiledModel& cm,
                                     const ResidualSymbols& s);

/// ρ and ∂ρ/∂(q, v, controls, a, λ), the structural non-zeros only.
class PointResidual {
 public:
  /// `controls`: the model inputs that are controls, in their column order; machine code per
  /// `mode` (MachineTape: the same bits as the interpreter).
  PointResidual(const Equations& eq, const CompiledModel& cm, const std::vector<size_t>& controls,
                Evaluation mode = Evaluation::Interpreter, const MachineCodeOptions& options = {});
  /// (row, column) of each derivative, in output order; columns q, v, the controls, a, λ.
  const std::vector<std::pair<size_t, size_t>>& pattern() const { return pattern_; }
  size_t rows() const { return rows_; }
  /// Inputs: the model's tape inputs, then a, λ, α. Outputs: ρ (rows()), then the derivatives.
  size_t num_inputs() const { return tape_.tape().num_inputs(); }
  size_t num_outputs() const { return tape_.tape().num_outputs(); }
  void eval(const double* in, double* out) const { tape_.eval(in, out); }
  /// Which evaluation runs, in words.
  std::string evaluation_note() const { return tape_.evaluation_note(); }

 private:
  size_t rows_ = 0;
  std::vector<std::pair<size_t, size_t>> pattern_;
  MachineTape tape_;
};

}  // namespace lagrange::collocation
