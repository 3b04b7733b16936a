#pragma once
// What every output sample must satisfy before a run may be called complete, whichever method
// integrated it (docs/theory.md §8.2): a finite state and finite energies, multipliers and
// residuals, and for a model that conserves energy, T + U kept.

#include <functional>
#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/stop_conditions.hpp"
#include "simulation/row_writer.hpp"

namespace lagrange {

/// The checks of one run's samples, in order; throws SimulationError at the first that fails.
class SampleChecks {
 public:
  /// `columns`: trajectory_columns(cm).
  SampleChecks(const CompiledModel& cm, const std::vector<std::string>& columns);
  /// The state y = (q, v) at t: every entry finite, else SimulationError naming the first.
  void state(double t, const double* y) const;
  /// A row written at t (its columns above): T, U, T + U, the multipliers, residuals and
  /// reactions finite (outputs are the user's and may be undefined somewhere); for a conservative
  /// model, |E − E₀| at most half the largest T + |U| of any sample so far, else the integrator
  /// stepped across a singularity (§8.2).
  void row(double t, const double* row);
  /// The sample of every run (simulate() and the Stepper): the row of the state y = (q, v) at t
  /// appended to `traj` by `rows`, then `also` (a run's own conditions on the row, e.g. the
  /// elements' fail_when) and row() applied to it; a row that fails is removed from `traj`
  /// before the SimulationError propagates. A row that passes adds a warning to `traj` for each
  /// of the model's warn_when conditions that holds there for the first time in this run.
  void append_row(RowWriter& rows, Dynamics& dyn, double t, const double* y, Trajectory& traj,
                  const std::function<void(const double* row)>& also = nullptr);

 private:
  void warn(const double* row, const double* parameters, double t, Trajectory& traj);

  const CompiledModel& cm_;
  std::vector<std::string> columns_;
  StopConditions cautions_;  // cm.warn_when
  std::vector<double> caution_g_;
  std::vector<bool> cautioned_;
  size_t kinetic_ = 0, outputs_end_ = 0;
  bool started_ = false;
  double t_prev_ = 0.0, t0_ = 0.0, e0_ = 0.0, scale_ = 0.0, scale_at_ = 0.0;
};

}  // namespace lagrange
