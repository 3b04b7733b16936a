// optimize() and verify() (lagrange/optimize.hpp): transcription, Ipopt, and the result read
// back as a trajectory.

#include "lagrange/optimize.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>

#include "optimize/energy_balance.hpp"
#include "optimize/ipopt_adapter.hpp"
#include "optimize/transcription.hpp"
#include "simulation/row_writer.hpp"
#include "support/seconds_since.hpp"

namespace lagrange {

namespace {

// A final value the constraints imply, missed by more than this (relative to 1 + |value|) once the
// final state is projected onto them: not reached (another branch, such as the pendulum hanging
// instead of upright, misses it by O(1); the projection leaves ~1e-12 of the collocation's drift).
constexpr double kImpliedTolerance = 1e-6;

/// What looks wrong but does not stop the solve: controls that no equation of motion, objective
/// term or path constraint uses (the optimiser can move nothing with them), and a periodic orbit
/// of free period whose phase nothing fixes (a family of solutions: Ipopt may wander along it).
std::vector<std::string> problem_warnings(const Equations& eq, const CompiledModel& cm,
                                          const OptimalControlSpec& spec) {
  std::vector<GiNaC::ex> used = dynamics_expressions(eq, cm);
  used.push_back(spec.integrand);
  used.push_back(spec.terminal);
  used.push_back(spec.mean_integrand);
  for (const PathConstraintSpec& p : spec.path) used.push_back(p.expr);
  std::vector<std::string> warnings;
  for (const ControlSpec& c : spec.controls) {
    const Input& input = eq.model->inputs.at(c.input);
    if (std::none_of(used.begin(), used.end(), [&](const GiNaC::ex& e) { return e.has(input.u); }))
      warnings.push_back(fmt::format(
          "{}: warning: control '{}' is used by no equation of motion, objective term or path "
          "constraint: the optimiser can move nothing with it, and its values are arbitrary",
          c.loc.str(), input.name));
  }
  if (!spec.periodic.empty() && spec.free_horizon && spec.initial &&
      std::none_of(spec.initial->begin(), spec.initial->end(),
                   [](const BoundaryValue& b) { return b.fixed(); }))
    warnings.push_back(fmt::format(
        "{}: warning: the phase of this periodic orbit is free (a free period and no fixed "
        "initial value): fix one initial value, such as a rate that is 0 at a turning point",
        spec.loc.str()));
  return warnings;
}

/// The problem as a homotopy stage poses it (docs/theory.md §10, "Homotopy"): its objective and
/// control bounds in place of the problem's.
OptimalControlSpec staged(const OptimalControlSpec& spec, const StageSpec& stage) {
  OptimalControlSpec s = spec;
  s.stages.clear();
  if (stage.replaces_objective) {
    s.maximize = stage.maximize;
    s.integrand = stage.integrand;
    s.terminal = stage.terminal;
    s.mean_integrand = stage.mean_integrand;
    s.objective_text = stage.objective_text;
  }
  for (const auto& [c, bounds] : stage.control_bounds) s.controls.at(c).bounds = bounds;
  if (stage.horizon) {  // the NLP keeps T as its variable 0: only its bounds change
    s.free_horizon = stage.horizon;
    s.horizon = std::clamp(s.horizon, stage.horizon->lower, stage.horizon->upper);
  }
  return s;
}

/// docs/theory.md §10, "Checks": the bounds x lies on, counted per quantity and side. A value
/// within 1e-6 (relative to 1 + |bound|) of a bound is on it (Ipopt's interior points stop about
/// 1e-8 inside); a fixed value (lower = upper) is a boundary condition, not counted.
std::vector<std::string> active_bounds(const collocation::Transcription& nlp, const double* x,
                                       const std::vector<double>& g, const std::vector<double>& xl,
                                       const std::vector<double>& xu, const std::vector<double>& gl,
                                       const std::vector<double>& gu) {
  struct Count {
    size_t order, on = 0, of = 0;
  };
  std::map<std::string, Count> counts;
  const auto count = [&](const std::string& quantity, double value, double lower, double upper) {
    if (quantity.empty() || lower == upper) return;
    for (const auto& [bound, side] : {std::pair{lower, "≥"}, std::pair{upper, "≤"}}) {
      if (!(std::fabs(bound) < 1e19)) continue;  // Ipopt's infinity: no bound
      const std::string key = fmt::format("{} {} {:g}", quantity, side, bound);
      auto [it, added] = counts.try_emplace(key, Count{counts.size()});
      ++it->second.of;
      if (std::fabs(value - bound) <= 1e-6 * (1 + std::fabs(bound))) ++it->second.on;
    }
  };
  for (size_t i = 0; i < xl.size(); ++i)
    count(nlp.variable_name(i, x).quantity, x[i], xl[i], xu[i]);
  for (size_t r = 0; r < g.size(); ++r) count(nlp.row_quantity(r), g[r], gl[r], gu[r]);
  std::vector<std::pair<size_t, std::string>> ordered;
  for (const auto& [key, c] : counts)
    if (c.on > 0)
      ordered.emplace_back(c.order, fmt::format("{} at {} of {} values", key, c.on, c.of));
  std::sort(ordered.begin(), ordered.end());
  std::vector<std::string> out;
  for (auto& [order, text] : ordered) out.push_back(std::move(text));
  return out;
}

/// At t = 0 and every collocation point, simulate's row (trajectory_columns: t, q, v, energies,
/// outputs, the forward dynamics' λ, residuals, reactions, loads) with the controls held, then
/// the controls (a polynomial control at t = 0: its first polynomial there) and the collocated
/// multipliers `lambda_<constraint>` (at t = 0, where none is collocated, the forward dynamics' λ).
/// A state where the forward dynamics fail keeps t, q, v and NaN in the columns they give.
Trajectory collocated(collocation::Transcription& nlp, Dynamics& dyn, const double* x,
                      const std::vector<std::string>& controls) {
  const CompiledModel& cm = dyn.model();
  Trajectory traj;
  traj.columns = trajectory_columns(cm);
  const size_t simulated = traj.columns.size(), nx = cm.nq + cm.nv, nu = controls.size();
  const size_t first_lambda =
      cm.m > 0 ? static_cast<size_t>(
                     std::find(traj.columns.begin(), traj.columns.end(), cm.constraint_names[0]) -
                     traj.columns.begin())
               : 0;
  for (const auto& n : controls) traj.columns.push_back(n);
  for (const auto& n : cm.constraint_names) traj.columns.push_back("lambda_" + n);
  RowWriter writer(cm);
  std::vector<double> row;
  const auto add = [&](double t, const double* X, const double* u, const double* lambda) {
    for (size_t c = 0; c < nu; ++c) dyn.hold_input(nlp.control_inputs()[c], u[c]);
    row.clear();
    try {
      writer.write(dyn, t, X, X + cm.nq, row);
    } catch (const SimulationError&) {
      row.assign(simulated, std::nan(""));
      row[0] = t;
      std::copy(X, X + nx, row.begin() + 1);
    }
    std::vector<double> forward_lambda;  // a copy: inserting from `row` into itself is undefined
    if (lambda == nullptr) {
      forward_lambda.assign(row.begin() + static_cast<long>(first_lambda),
                            row.begin() + static_cast<long>(first_lambda + cm.m));
      lambda = forward_lambda.data();
    }
    row.insert(row.end(), u, u + nu);
    row.insert(row.end(), lambda, lambda + cm.m);
    traj.data.insert(traj.data.end(), row.begin(), row.end());
  };
  add(0.0, nlp.state(x, 0, 0), nlp.control(x, 0, 0), nullptr);
  for (int k = 0; k < nlp.intervals(); ++k)
    for (int j = 1; j <= nlp.scheme().degree; ++j)
      add(nlp.time(x, k, j), nlp.state(x, k, j), nlp.control(x, k, j), nlp.multipliers(x, k, j));
  return traj;
}

}  // namespace

OptimizeResult optimize(const Equations& eq, std::shared_ptr<const CompiledModel> cm, Dynamics& dyn,
                        const OptimalControlSpec& spec, const std::vector<double>& q0,
                        const std::vector<double>& v0, const OptimizeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  OptimizeResult r;
  r.warnings = problem_warnings(eq, *cm, spec);
  r.intervals = options.intervals > 0 ? options.intervals : spec.intervals;
  r.degree = options.degree > 0 ? options.degree : spec.degree;
  for (const ControlSpec& c : spec.controls)
    r.control_names.push_back(eq.model->inputs[c.input].name);
  // docs/theory.md §10, "Homotopy": each stage starts where the last one ended, the problem
  // itself where the last stage ended.
  collocation::StageStart from;        // x null: the problem's guess
  collocation::IpoptOutcome previous;  // the last stage's solve: its multipliers
  using IpoptOptions = std::vector<std::pair<std::string, std::string>>;
  // Transcribes `s` from `from` and solves it, adding the times to r (set-up since `setup_from`).
  const auto solve = [&](const OptimalControlSpec& s, const IpoptOptions& ipopt,
                         std::chrono::steady_clock::time_point setup_from) {
    std::pair<std::unique_ptr<collocation::Transcription>, collocation::IpoptOutcome> done;
    done.first = std::make_unique<collocation::Transcription>(
        eq, cm, dyn, s, r.intervals, r.degree, q0, v0, options.hessian, &from, options.evaluation,
        options.machine_code);
    r.setup_seconds += seconds_since(setup_from);
    const auto solve_start = std::chrono::steady_clock::now();
    done.second = collocation::solve_with_ipopt(*done.first, ipopt, options.verbose,
                                                options.interrupt, &previous);
    r.solve_seconds += seconds_since(solve_start);
    r.function_seconds += done.second.function_seconds;
    return done;
  };
  for (const StageSpec& stage : spec.stages) {
    const auto stage_start = std::chrono::steady_clock::now();
    const OptimalControlSpec s = staged(spec, stage);
    from.track = stage.track;
    IpoptOptions ipopt = options.ipopt;
    ipopt.insert(ipopt.end(), stage.ipopt.begin(), stage.ipopt.end());
    auto [nlp, out] = solve(s, ipopt, stage_start);
    from.dae_hessian = nlp->dae_hessian();
    from.residual = nlp->residual();
    const double tracking = nlp->tracking(out.x.data());
    r.stages.push_back({stage.name, out.optimal, out.status, out.iterations,
                        (nlp->objective(out.x.data()) - tracking) * (nlp->maximize() ? -1.0 : 1.0),
                        tracking, seconds_since(stage_start)});
    previous = std::move(out);
    from.x = &previous.x;
  }
  from.track = 0.0;
  auto [final_nlp, out] =
      solve(spec, options.ipopt, spec.stages.empty() ? start : std::chrono::steady_clock::now());
  collocation::Transcription& nlp = *final_nlp;
  r.hessian_note = nlp.hessian_note();
  r.hessian_evaluation = nlp.hessian_evaluation();
  r.residual_evaluation = nlp.residual_evaluation();
  r.optimal = out.optimal;
  r.status = out.status;
  r.iterations = out.iterations;
  r.exact_hessian = out.exact_hessian;
  const double* x = out.x.data();
  r.horizon = nlp.horizon(x);
  r.objective = nlp.objective(x) * (nlp.maximize() ? -1.0 : 1.0);

  // The worst violation of a constraint's bounds at the result.
  std::vector<double> g(nlp.constraints()), xl(nlp.variables()), xu(nlp.variables()),
      gl(nlp.constraints()), gu(nlp.constraints());
  nlp.bounds(xl.data(), xu.data(), gl.data(), gu.data());
  nlp.constraint_values(x, g.data());
  for (size_t i = 0; i < g.size(); ++i) {
    const double v = std::isnan(g[i]) ? INFINITY : std::max({gl[i] - g[i], g[i] - gu[i], 0.0});
    if (v > r.violation || (i == 0 && v > 0)) {
      r.violation = v;
      r.worst_constraint = nlp.describe(i, x);
    }
  }
  r.active_bounds = active_bounds(nlp, x, g, xl, xu, gl, gu);
  r.energy_balance = collocation::energy_balance(eq, nlp, x);
  // A final value the constraints imply is checked, not imposed. Its gap includes the
  // collocation's drift off the constraints; projected back onto them (the imposed final values
  // kept), a gap that remains means another branch (docs/theory.md §10, "Constrained models").
  for (const auto& implied : nlp.implied_final_gaps(x)) {
    if (implied.gap > r.violation) {
      r.violation = implied.gap;
      r.worst_constraint = implied.what;
    }
    if (r.optimal && implied.projected > kImpliedTolerance * (1 + std::fabs(implied.value))) {
      r.optimal = false;
      r.status = fmt::format(
          "optimal, but the {} is off by {:.3g}: another branch of the constraints (guess a path "
          "near the target)",
          implied.what, implied.projected);
    }
  }
  // docs/theory.md §10, "Polynomial controls": a polynomial control's mean over an interval is
  // Σ_j b_j U_{k,j} (the quadrature is exact for its degree d − 1).
  const size_t nu = spec.controls.size();
  for (size_t c = 0; c < nu; ++c) r.polynomial.push_back(nlp.polynomial(c));
  r.controls.assign(static_cast<size_t>(r.intervals) * nu, 0.0);
  for (int k = 0; k < r.intervals; ++k)
    for (int j = 1; j <= r.degree; ++j) {
      const double* u = nlp.control(x, k, j);
      r.control_points.insert(r.control_points.end(), u, u + nu);
      for (size_t c = 0; c < nu; ++c)
        r.controls[static_cast<size_t>(k) * nu + c] +=
            r.polynomial[c] ? nlp.scheme().b[static_cast<size_t>(j - 1)] * u[c]
                            : (j == 1 ? u[c] : 0.0);
    }
  r.trajectory = collocated(nlp, dyn, x, r.control_names);
  if (out.interrupted) {
    r.optimal = false;
    r.status = "interrupted after " + std::to_string(r.iterations) + " iterations";
    r.trajectory.status = Trajectory::Status::Interrupted;
    r.trajectory.message = r.status;
  } else if (!r.optimal) {
    r.trajectory.status = Trajectory::Status::Failed;
    r.trajectory.message = "not optimal: " + r.status;
  }
  dyn.release_inputs();
  return r;
}

namespace {

/// controls_at with the scheme of the result's degree made once.
void controls_at(const OptimizeResult& result, const collocation::Radau& scheme, double t,
                 double* u) {
  const int N = result.intervals, d = result.degree;
  const size_t nu = result.control_names.size();
  const double s = t / result.horizon * N;
  const int k = std::clamp(static_cast<int>(std::floor(s)), 0, N - 1);
  std::vector<double> basis;
  for (size_t c = 0; c < nu; ++c) {
    if (!result.polynomial[c]) {
      u[c] = result.controls[static_cast<size_t>(k) * nu + c];
      continue;
    }
    if (basis.empty()) basis = collocation::point_basis(scheme, s - k);
    u[c] = 0.0;
    for (int j = 0; j < d; ++j)
      u[c] += basis[static_cast<size_t>(j)] *
              result.control_points[(static_cast<size_t>(k * d + j)) * nu + c];
  }
}

}  // namespace

void controls_at(const OptimizeResult& result, double t, double* u) {
  controls_at(result, collocation::radau(result.degree), t, u);
}

VerifyResult verify(Dynamics& dyn, const OptimalControlSpec& spec, const OptimizeResult& result,
                    SimulationOptions options) {
  const CompiledModel& cm = dyn.model();
  const Trajectory& traj = result.trajectory;
  const size_t cols = traj.columns.size();
  const int N = result.intervals;
  const double T = result.horizon;
  std::vector<size_t> inputs;
  for (const ControlSpec& c : spec.controls) inputs.push_back(c.input);
  const collocation::Radau scheme = collocation::radau(result.degree);
  dyn.set_input_law(inputs, [&](double t, const double*, const double*, double* u) {
    controls_at(result, scheme, t, u);
  });
  std::vector<double> q0(traj.data.begin() + 1, traj.data.begin() + 1 + static_cast<long>(cm.nq));
  std::vector<double> v0(traj.data.begin() + 1 + static_cast<long>(cm.nq),
                         traj.data.begin() + 1 + static_cast<long>(cm.nq + cm.nv));
  options.t0 = 0.0;
  options.t_end = T;
  options.output_step = T / (N * 8.0);
  const Trajectory sim = simulate(dyn, options, q0, v0);
  dyn.release_inputs();
  VerifyResult v;
  if (sim.status != Trajectory::Status::Complete) v.message = sim.message;
  const size_t sc = sim.columns.size(), rows = sim.rows();
  auto sim_at = [&](double t, size_t i) {
    size_t r = 0;
    while (r + 1 < rows && sim.data[(r + 1) * sc] < t) ++r;
    if (r + 1 >= rows) return sim.data[r * sc + 1 + i];
    const double t0 = sim.data[r * sc], t1 = sim.data[(r + 1) * sc];
    const double s = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
    return (1 - s) * sim.data[r * sc + 1 + i] + s * sim.data[(r + 1) * sc + 1 + i];
  };
  // At the mesh points (samples of the simulation: the output step divides T/N).
  for (size_t r = 0; r < traj.rows() && rows > 0; r += static_cast<size_t>(result.degree))
    for (size_t i = 0; i < cm.nq + cm.nv; ++i) {
      const double gap = std::fabs(sim_at(traj.data[r * cols], i) - traj.data[r * cols + 1 + i]);
      v.largest_gap = std::max(v.largest_gap, gap);
      if (r + 1 == traj.rows()) v.final_gap = std::max(v.final_gap, gap);
    }
  return v;
}

}  // namespace lagrange
