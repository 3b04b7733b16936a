#pragma once
// Runs a model's dynamics through an integrator into a trajectory on a uniform grid.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "lagrange/dynamics.hpp"
#include "lagrange/integrator.hpp"
#include "lagrange/model.hpp"

namespace lagrange {

/// A sampled trajectory; `status` says whether it is complete.
struct Trajectory {
  std::vector<std::string>
      columns;  ///< t, q…, q_dot…, kinetic, potential, energy, outputs…, λ…, residuals
  std::vector<double> data;  ///< row-major samples
  enum class Status { Complete, Failed, Interrupted } status = Status::Complete;
  std::string message;  ///< failure reason (empty when complete)
  double failure_time = 0.0;
  std::vector<std::string> notes;  ///< e.g. what the initial-state projection changed
  /// Results that may not mean what they seem (CompiledModel::warn_when), once per condition.
  std::vector<std::string> warnings;
  /// Largest ‖RᵀR − 1‖_F of any free body before it was re-orthonormalised, after an internal
  /// step or at an output sample (the drift the integrator leaves over one step; 0 without free
  /// bodies).
  double rotation_drift = 0.0;
  IntegratorStats stats;
  /// The `stop_when` condition that ended the run (empty when none did) and when it became true;
  /// the last row is at that time.
  std::string stopped_by;
  double stop_time = 0.0;

  size_t rows() const { return columns.empty() ? 0 : data.size() / columns.size(); }
  /// Value at row r of the named column; throws std::out_of_range for an unknown name.
  double at(size_t r, const std::string& column) const;
  size_t column_index(const std::string& column) const;
  const char* status_name() const;
};

/// Baumgarte α when a model does not set one (methods that do not project between samples).
constexpr double kDefaultBaumgarte = 20.0;

/// The Baumgarte rate a run with `method` uses (docs/theory.md §4.3, "Choosing α"): the model's α
/// when it sets one; otherwise 0 — post-stabilisation by projection alone — for the explicit and
/// fixed-step methods, which project after every step that drifts, and kDefaultBaumgarte for
/// cvode and ida, which correct only at output samples, and for any method without projection.
double baumgarte_rate(const Stabilization& stabilization, const std::string& method);

/// Builds the exact Jacobians a run integrates on, for the workspace it evaluates, from its start
/// (t0, y0) (over a DynamicsJacobian derived once per model). Each throws std::invalid_argument
/// when the model has none, std::runtime_error when it cannot be evaluated at y0.
struct JacobianSource {
  /// Of the first-order form (ode_jacobian in analysis.hpp): cvode:jacobian, auto.
  std::function<OdeJacobian(Dynamics& dynamics, double t0, const std::vector<double>& y0)> ode;
  /// The Newton matrix of the DAE (dae_jacobian in analysis.hpp): ida:jacobian.
  std::function<DaeJacobian(Dynamics& dynamics, double t0, const std::vector<double>& y0)> dae;
  explicit operator bool() const { return ode || dae; }
};

/// How simulate() runs: the time grid, the integrator, the Jacobian it may use, projection.
struct SimulationOptions {
  double t0 = 0.0;
  double t_end = 10.0;
  double output_step = 0.01;
  IntegratorOptions integrator;
  /// The exact Jacobian of the first-order form (ode_jacobian in analysis.hpp), handed to the
  /// integrator as OdeProblem::jacobian; cvode:jacobian needs it. It refers to one workspace:
  /// the one simulate() is given.
  OdeJacobian jacobian;
  /// Where cvode:jacobian and auto get `jacobian` when it is empty, and ida:jacobian its Newton
  /// matrix, for the workspace they run on (simulate(), the Stepper and a sweep's cases alike:
  /// run_jacobian, run_dae_jacobian).
  JacobianSource jacobian_source;
  /// At output samples (IDA: there only) project onto C = 0, Ċ = 0 when max |C| or |Ċ| exceeds
  /// projection_tol, after each internal step of an ODE method when they exceed
  /// step_drift_tolerance(); replace a free body's R by the nearest rotation when ‖RᵀR − 1‖_F
  /// exceeds projection_tol.
  bool project = true;
  double projection_tol = 1e-11;
  /// Between samples (after internal steps of ODE methods) the constraints are projected only
  /// when max |C| or max |Ċ| exceeds this; 0: step_drift_tolerance() derives it from atol.
  double step_drift_tol = 0.0;
  bool project_initial = true;  ///< false: fail when the initial state is inconsistent
  const std::atomic<bool>* interrupt = nullptr;  ///< set asynchronously to stop cleanly
  std::function<void(double t)> progress;        ///< called at each output sample
};

/// The drift allowed between samples (docs/theory.md §4.3, "Projecting when the drift matters"):
/// step_drift_tol when set, else max(projection_tol, integrator.atol).
double step_drift_tolerance(const SimulationOptions& options);

/// An initial state checked against C = 0, Ċ = 0 and, where needed, projected onto them
/// (docs/theory.md §4.3).
struct InitialConsistency {
  bool was_consistent = true;     ///< max |C| and max |Ċ| were within tol: nothing changed
  bool consistent = true;         ///< max |C| and max |Ċ| are within tol now
  std::vector<double> C0, Cdot0;  ///< at the given state
  std::vector<double> C, Cdot;    ///< at the projected state (the best one found)
  ProjectionResult projection;
  /// Not consistent, but the projection reaches C = 0, Ċ = 0 when no coordinate is held fixed.
  bool blocked_by_fixed = false;
  std::string changes;  ///< one line "\n  name: old -> new" per changed coordinate or velocity

  /// "initial state was inconsistent (max |C| = …, max |Ċ| = …); projected onto the
  /// constraints (|Δq| = …, |Δv| = …):" and the changes.
  std::string note() const;
};

/// Checks C = 0 and Ċ = 0 to `tol` at (t0, q, v) and, if they fail, projects q and v in place
/// keeping the model's fixed coordinates (Dynamics::try_project). Never throws for a state that
/// cannot be made consistent: `consistent` says so, and the other fields say why.
InitialConsistency make_initial_state_consistent(Dynamics& dynamics, double t0,
                                                 std::vector<double>& q, std::vector<double>& v,
                                                 double tol = 1e-11);

/// True for the methods that integrate on the exact Jacobian: cvode:jacobian, ida:jacobian, and
/// auto (which may choose or switch to cvode:jacobian).
bool uses_jacobian(const std::string& method);

/// The Jacobian a run with `options` integrates on from (t0, y0) on `dynamics`: for cvode:jacobian
/// and auto, options.jacobian, else one built by options.jacobian_source.ode; empty for
/// other methods and for auto when none can be had (auto then runs DOP853 throughout). For
/// cvode:jacobian without one: std::invalid_argument, or SimulationError at t0 when it cannot be
/// evaluated there.
OdeJacobian run_jacobian(Dynamics& dynamics, const SimulationOptions& options, double t0,
                         const std::vector<double>& y0);

/// The Newton matrix an ida:jacobian run integrates on from (t0, y0), y0 = (q, v, λ), built by
/// options.jacobian_source.dae; empty for other methods. Without a source:
/// std::invalid_argument; SimulationError at t0 when it cannot be evaluated there.
DaeJacobian run_dae_jacobian(Dynamics& dynamics, const SimulationOptions& options, double t0,
                             const std::vector<double>& y0);

/// Simulate from (q0, v0). Never throws for numerical failures: the trajectory computed so far
/// is returned with status Failed and the reason (SimulationError message).
Trajectory simulate(Dynamics& dynamics, const SimulationOptions& options, std::vector<double> q0,
                    std::vector<double> v0);

}  // namespace lagrange
