#pragma once
// A tape the optimiser evaluates many times: on machine code once it is had (docs/theory.md §8,
// the MachineCode cache; compiled at once or beside the solve per Evaluation), else on the
// interpreter. Both compute the same bits, so the switch changes no iterate.

#include <memory>
#include <string>
#include <vector>

#include "lagrange/dynamics.hpp"
#include "lagrange/machine_code.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {
namespace dynamics {
struct NativeTapes;
}

namespace collocation {

/// One tape with its work array and, when asked for, its machine code.
class MachineTape {
 public:
  MachineTape();
  explicit MachineTape(Tape tape);
  MachineTape(MachineTape&&) noexcept;
  MachineTape& operator=(MachineTape&&) noexcept;
  ~MachineTape();
  const Tape& tape() const { return tape_; }
  /// Machine code per `mode` (Interpreter: none); eval uses it once it is ready.
  void use_machine_code(Evaluation mode, const MachineCodeOptions& options);
  /// Which evaluation runs, in words ("machine code (from the cache)", "interpreter (…)").
  std::string evaluation_note() const;
  /// The tape's outputs at inputs `in` into `out` (tape().num_outputs() values).
  void eval(const double* in, double* out) const;

 private:
  Tape tape_;
  mutable std::vector<double> work_;
  std::unique_ptr<dynamics::NativeTapes> native_;
};

}  // namespace collocation
}  // namespace lagrange
