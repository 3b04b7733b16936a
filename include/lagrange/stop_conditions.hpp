#pragma once
// `stop_when:` conditions (docs/model-language.md, "Stop conditions"): `lhs < rhs` or `lhs > rhs`
// over the trajectory's columns and the parameters, compiled to one tape; a run ends at the
// first time one of them becomes true, located to the integrator's tolerance.

#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

/// The compiled conditions of a model; g_i > 0 exactly when condition i holds. One per run
/// (evaluate uses scratch space).
class StopConditions {
 public:
  StopConditions() = default;
  /// Compiles cm.stop_when against `columns` (trajectory_columns(cm)) and cm's parameters;
  /// ModelError at the condition for an unknown name or a vector-valued side.
  StopConditions(const CompiledModel& cm, const std::vector<std::string>& columns);
  /// The same for other conditions over those columns (cm.fail_when).
  StopConditions(const std::vector<StopSpec>& specs, const CompiledModel& cm,
                 const std::vector<std::string>& columns);

  bool empty() const { return specs_.empty(); }
  size_t size() const { return specs_.size(); }
  const StopSpec& spec(size_t i) const { return specs_[i]; }
  /// g (size()) for one trajectory row (the columns given above) and the parameter values.
  void evaluate(const double* row, const double* parameters, double* g) const;

 private:
  std::vector<StopSpec> specs_;
  size_t columns_ = 0, parameters_ = 0;
  Tape tape_;
  mutable std::vector<double> in_, work_;
};

}  // namespace lagrange
