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
      step_tol_(step_drift_tolerance(options)),
      weigh_moves_(options.step_drift_tol <= 0.0 &&
                   corrects_only_at_samples(options.integrator.method)) {}

bool corrects_only_at_samples(const std::string& method) {
  return method.rfind("cvode", 0) == 0 || method.rfind("ida", 0) == 0;
}

bool DriftCorrection::correct(double t, double* y, double allowed) {
  const bool rotated = correct_rotations(y, allowed);
  return correct_constraints(t, y, allowed) || rotated;
}

bool DriftCorrection::correct_rotations(double* y, double allowed) {
  const double drift =
      orthonormalize_rotations(dynamics_.model(), y, options_.project ? allowed : HUGE_VAL);
  rotation_drift_ = std::max(rotation_drift_, drift);
  return options_.project && drift > allowed;
}

bool DriftCorrection::correct_constraints(double t, double* y, double allowed) {
  const CompiledModel& cm = dynamics_.model();
  if (!options_.project || cm.m == 0) return false;
  dynamics_.constraints(t, y, y + cm.nq, C_.data(), Cdot_.data());
  if (max_abs(C_) <= allowed && max_abs(Cdot_) <= allowed) return false;
  dynamics_.project(t, y, y + cm.nq, none_fixed_, 1e-13);
  return true;
}

// docs/theory.md §4.3, "Projecting when the drift matters": a BDF method pays for a correction
// with a restart at order 1, and Baumgarte's term (α > 0 for these methods) already holds the
// constraints' drift at a few steps' local errors. So a projection that would move no component
// by more than kBaumgarteHeldDrift times the error test's tolerance rtol |y_i| + atol is left to
// the next sample's check. R's orthonormality has no such term: it is corrected as for any method.
bool DriftCorrection::after_step(double t, double* y) {
  if (!weigh_moves_) return correct(t, y, step_tol_);
  const bool rotated = correct_rotations(y, step_tol_);
  const CompiledModel& cm = dynamics_.model();
  trial_.assign(y, y + cm.nq + cm.nv);
  if (!correct_constraints(t, trial_.data(), step_tol_)) return rotated;
  const double rtol = options_.integrator.rtol, atol = options_.integrator.atol;
  bool beyond = false;
  for (size_t i = 0; i < trial_.size() && !beyond; ++i)
    beyond = std::abs(trial_[i] - y[i]) > kBaumgarteHeldDrift * (rtol * std::abs(y[i]) + atol);
  if (beyond) std::copy(trial_.begin(), trial_.end(), y);
  return beyond || rotated;
}

}  // namespace lagrange
