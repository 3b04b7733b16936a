#pragma once
// The drift correction a run applies after every internal step and at output samples: free
// bodies' R back onto SO(3), then the state onto C = 0, Ċ = 0 (docs/theory.md §4.3, §4.4).
// simulate() and the Stepper share it.

#include <string>
#include <vector>

#include "lagrange/dynamics.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

/// Corrects a state y = (q, v) in place as `options` ask (project, projection_tol).
class DriftCorrection {
 public:
  DriftCorrection(Dynamics& dynamics, const SimulationOptions& options);
  /// docs/theory.md §4.3, §4.4: R ← nearest rotation where ‖RᵀR − 1‖_F > tol, then a projection
  /// onto C = 0, Ċ = 0 where max |C| or |Ċ| > tol (every coordinate may move); true when y moved.
  /// At output samples: tol = projection_tol.
  bool operator()(double t, double* y) { return correct(t, y, options_.projection_tol); }
  /// After an internal step: R and the constraints only when their drift exceeds
  /// step_drift_tolerance() (docs/theory.md §4.3, "Projecting when the drift matters"; §4.4).
  /// For a method that restarts after a correction (BDF), and with no step_drift_tol set, the
  /// constraints only when their projection would move some component by more than
  /// kBaumgarteHeldDrift (rtol |y_i| + atol).
  bool after_step(double t, double* y);
  /// How many of the error test's tolerances a BDF method's constraint drift may reach before
  /// its state is projected (docs/theory.md §4.3, measured there).
  static constexpr double kBaumgarteHeldDrift = 10.0;
  /// Largest ‖RᵀR − 1‖_F seen before a correction (Trajectory::rotation_drift).
  double largest_rotation_drift() const { return rotation_drift_; }

 private:
  bool correct(double t, double* y, double allowed);
  bool correct_rotations(double* y, double allowed);
  bool correct_constraints(double t, double* y, double allowed);

  Dynamics& dynamics_;
  const SimulationOptions& options_;
  std::vector<double> C_, Cdot_;
  std::vector<bool> none_fixed_;
  double rotation_drift_ = 0.0;
  double step_tol_;
  bool weigh_moves_;           // the correction is weighed against the error test first
  std::vector<double> trial_;  // the corrected state being weighed
};

/// True for the methods that correct drift only at output samples and lose their history (order,
/// step) when the state is changed under them: cvode, cvode:jacobian, ida, ida:jacobian.
bool corrects_only_at_samples(const std::string& method);

}  // namespace lagrange
