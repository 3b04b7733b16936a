#pragma once
// `stop_when:` conditions (docs/model-language.md, "Stop conditions"): `lhs < rhs` or `lhs > rhs`
// over the trajectory's columns and the parameters, compiled to one tape; a run ends at the
// first time one of them becomes true, located to the integrator's tolerance.

#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

/// One run's view of a model's compiled conditions (cm's tape and scratch space; evaluate uses
/// the scratch, so one per run). Making one runs no symbolic code.
class StopConditions {
 public:
  enum class Kind { Stop, Fail, Warn };  ///< cm.stop_when, cm.fail_when, cm.warn_when

  StopConditions() = default;
  /// cm's conditions of `kind`; `cm` must outlive this.
  explicit StopConditions(const CompiledModel& cm, Kind kind = Kind::Stop);

  bool empty() const { return size() == 0; }
  size_t size() const { return specs_ ? specs_->size() : 0; }
  const StopSpec& spec(size_t i) const { return (*specs_)[i]; }
  /// g (size()) for one trajectory row (trajectory_columns(cm)) and the parameter values.
  void evaluate(const double* row, const double* parameters, double* g) const;

 private:
  const std::vector<StopSpec>* specs_ = nullptr;
  const Tape* tape_ = nullptr;
  size_t columns_ = 0, parameters_ = 0;
  mutable std::vector<double> in_, work_;
};

}  // namespace lagrange
