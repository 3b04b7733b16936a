// One case of a study on a worker's Dynamics: the per-case inputs read from the model file, and
// the run itself, made as `simulate --set` makes it.

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "lagrange/dynamics.hpp"
#include "lagrange/sweep.hpp"
#include "support/seconds_since.hpp"

namespace lagrange::sweep {

CaseInput case_input(const Model& case_model, const CompiledModel& base,
                     const SimulationOptions& options) {
  CaseInput in;
  ModelInitialState initial = model_initial_state(case_model);
  in.q0 = std::move(initial.q0);
  in.v0 = std::move(initial.v0);
  for (const auto& p : case_model.parameters) in.parameters.push_back(p.value);
  // The SO(3) drift rate is the compiled model's last parameter when it has free bodies.
  if (!base.parameter_names.empty() && base.parameter_names.back() == "stabilization.gamma")
    in.parameters.push_back(case_model.stabilization.gamma);
  bool same = in.q0.size() == base.nq && in.v0.size() == base.nv &&
              in.parameters.size() == base.np &&
              case_model.constraints.size() == base.constraint_names.size() &&
              case_model.inputs.size() == base.k;
  for (size_t i = 0; same && i < case_model.parameters.size(); ++i)
    same = case_model.parameters[i].name == base.parameter_names[i];
  if (!same)
    throw StudyError(fmt::format(
        "these values change the structure of {} ({} coordinates and {} constraints instead of "
        "{} and {}): a study varies values that one derivation covers; run such cases "
        "as separate studies",
        case_model.file, in.q0.size(), case_model.constraints.size(), base.nq, base.m));
  in.options = options;
  in.baumgarte = baumgarte_rate(case_model.stabilization, options.integrator.method);
  return in;
}

CaseResult run_case(Dynamics& dyn, const CaseInput& input, const std::vector<Metric>& metrics,
                    Trajectory* kept) {
  const auto start = std::chrono::steady_clock::now();
  CaseResult result;
  Trajectory traj;
  try {
    // As prepare() and run_simulate() do: the parameters, the initial state made consistent
    // with the default projection tolerance, then the run (docs/theory.md §4.3).
    dyn.set_parameters(input.parameters);
    dyn.set_baumgarte(input.baumgarte);
    std::vector<double> q = input.q0, v = input.v0;
    const InitialConsistency ic =
        make_initial_state_consistent(dyn, 0.0, q, v, SimulationOptions{}.projection_tol);
    if (ic.consistent) {
      traj = simulate(dyn, input.options, q, v);
    } else {
      traj.status = Trajectory::Status::Failed;
      traj.message = fmt::format(
          "the initial state cannot be made consistent with the constraints (max |C| = {:.3g}, "
          "max |Cdot| = {:.3g} after projection)",
          ic.projection.residual, ic.projection.rate_residual);
    }
  } catch (const std::exception& e) {
    traj.status = Trajectory::Status::Failed;
    traj.message = e.what();
  }
  result.status = traj.status;
  result.reason = traj.message;
  result.failure_time = traj.failure_time;
  if (traj.rows() > 0) {
    const RowAt row_at = rows_between_samples(dyn, input.options, traj);
    for (const auto& m : metrics)
      result.metrics.push_back(evaluate(m, traj, input.parameters, row_at));
  } else
    result.metrics.assign(metrics.size(), std::nan(""));
  result.wall_seconds = seconds_since(start);
  if (kept) *kept = std::move(traj);
  return result;
}

CaseResult run_case(Dynamics& dyn, const CaseRead& read, const std::vector<Metric>& metrics,
                    Trajectory* kept) {
  if (read.input) return run_case(dyn, *read.input, metrics, kept);
  CaseResult r;
  r.status = Trajectory::Status::Failed;
  r.reason = read.rejected;
  r.metrics.assign(metrics.size(), std::nan(""));
  return r;
}

}  // namespace lagrange::sweep
