// A run's view of its model's compiled conditions (docs/model-language.md, "Stop conditions";
// compiled with the model in src/dynamics/compile_conditions.cpp).
#include "lagrange/stop_conditions.hpp"

#include <algorithm>

namespace lagrange {

StopConditions::StopConditions(const CompiledModel& cm, Kind kind)
    : specs_(kind == Kind::Stop   ? &cm.stop_when
             : kind == Kind::Fail ? &cm.fail_when
                                  : &cm.warn_when),
      tape_(kind == Kind::Stop   ? &cm.stop_tape
            : kind == Kind::Fail ? &cm.fail_tape
                                 : &cm.warn_tape),
      parameters_(cm.np) {
  if (specs_->empty()) return;
  columns_ = tape_->num_inputs() - parameters_;
  in_.resize(tape_->num_inputs());
  work_.resize(tape_->work_size());
}

void StopConditions::evaluate(const double* row, const double* parameters, double* g) const {
  std::copy(row, row + columns_, in_.begin());
  std::copy(parameters, parameters + parameters_, in_.begin() + static_cast<long>(columns_));
  tape_->eval(in_.data(), g, work_.data());
}

}  // namespace lagrange
