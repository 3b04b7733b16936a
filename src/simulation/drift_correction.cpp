#include "simulation/drift_correction.hpp"

#include <algorithm>
#include <cmath>

#include "simulation/max_abs.hpp"

namespace lagrange {

DriftCorrection::DriftCorrection(Dynamics& dynamics, const SimulationOptions& options)
    : dynamics_(dynamics),
      options_(options),
      C_(dynamics.model().m),
      Cdot_(dynamics.model().m),
      none_fixed_(dynamics.model().nq, false),
      step_tol_(step_drift_tolerance(options)) {}

bool DriftCorrection::correct(double t, double* y, double allowed) {
  const CompiledModel& cm = dynamics_.model();
  const double drift = orthonormalize_rotations(cm, y, options_.project ? allowed : HUGE_VAL);
  rotation_drift_ = std::max(rotation_drift_, drift);
  if (!options_.project) return false;
  bool moved = drift > allowed;
  if (cm.m > 0) {
    dynamics_.constraints(t, y, y + cm.nq, C_.data(), Cdot_.data());
    if (max_abs(C_) > allowed || max_abs(Cdot_) > allowed) {
      dynamics_.project(t, y, y + cm.nq, none_fixed_, 1e-13);
      moved = true;
    }
  }
  return moved;
}

}  // namespace lagrange
