#pragma once
// The second derivatives of one scalar expression along chosen tape inputs, the structural
// non-zeros of its lower triangle only, compiled onto one tape (docs/theory.md §10, "Hessian"),
// evaluated on machine code when it is had (docs/theory.md §8).

#include <ginac/ginac.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "optimize/machine_tape.hpp"

namespace lagrange::collocation {

/// ∂²s/∂c_a∂c_b for columns a ≥ b, where column a is input `columns[a]` of `inputs`.
class SecondDerivatives {
 public:
  SecondDerivatives() = default;
  SecondDerivatives(const GiNaC::ex& s, const std::vector<GiNaC::symbol>& inputs,
                    const std::vector<size_t>& columns);
  /// (a, b), a ≥ b, of each output, in output order.
  const std::vector<std::pair<size_t, size_t>>& pattern() const { return pattern_; }
  const Tape& tape() const { return tape_.tape(); }
  /// Machine code for the tape per `mode` (MachineTape).
  void use_machine_code(Evaluation mode, const MachineCodeOptions& options) {
    tape_.use_machine_code(mode, options);
  }
  /// Which evaluation runs, in words ("machine code (from the cache)", "interpreter (…)").
  std::string evaluation_note() const { return tape_.evaluation_note(); }
  /// The derivatives at the tape input vector `in` into `out` (pattern().size() values).
  void eval(const std::vector<double>& in, std::vector<double>& out) const;

 private:
  std::vector<std::pair<size_t, size_t>> pattern_;
  MachineTape tape_;
};

}  // namespace lagrange::collocation
