#pragma once
// One output row of a trajectory: t, q, v, T, U, T + U, outputs, λ, max|C|, max|Ċ|, reactions,
// loads (trajectory_columns). simulate() and the Stepper write their samples with it.

#include <vector>

#include "lagrange/dynamics.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

/// Appends rows to a Trajectory; its buffers are sized once, and one forward() gives λ together
/// with C and Ċ.
class RowWriter {
 public:
  explicit RowWriter(const CompiledModel& cm);
  /// Appends the row of (t, q, v) to traj.data.
  void append(Dynamics& dyn, double t, const double* q, const double* v, Trajectory& traj);
  /// Appends the row of (t, q, v) to `row` (a stop condition's values are read from it).
  void write(Dynamics& dyn, double t, const double* q, const double* v, std::vector<double>& row);

 private:
  double load_value(const LoadColumn& load) const;  // after forward(): a_ and lambda_ are set
  std::vector<double> obs_, qdot_, a_, lambda_, C_, Cdot_;
};

}  // namespace lagrange
