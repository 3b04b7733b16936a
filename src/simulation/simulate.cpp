#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lagrange/error.hpp"
#include "lagrange/integration_failure.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

std::vector<std::string> trajectory_columns(const CompiledModel& cm) {
  std::vector<std::string> cols{"t"};
  for (const auto& q : cm.coordinate_names) cols.push_back(q);
  for (const auto& v : cm.velocity_names) cols.push_back(v);
  cols.insert(cols.end(), {"kinetic", "potential", "energy"});
  for (const auto& o : cm.output_names) cols.push_back(o);
  if (cm.m > 0) {
    for (const auto& c : cm.constraint_names) cols.push_back(c);
    cols.insert(cols.end(), {"constraint_residual", "constraint_rate_residual"});
    for (const auto& r : cm.reaction_names) cols.push_back(r);
  }
  return cols;
}

size_t Trajectory::column_index(const std::string& column) const {
  auto it = std::find(columns.begin(), columns.end(), column);
  if (it == columns.end()) throw std::out_of_range("no column '" + column + "' in the trajectory");
  return static_cast<size_t>(it - columns.begin());
}

double Trajectory::at(size_t r, const std::string& column) const {
  return data.at(r * columns.size() + column_index(column));
}

const char* Trajectory::status_name() const {
  switch (status) {
    case Status::Complete:
      return "complete";
    case Status::Failed:
      return "failed";
    case Status::Interrupted:
      return "interrupted";
  }
  return "unknown";
}

namespace {

double max_abs(const std::vector<double>& x) {
  double r = 0.0;
  for (double v : x) r = std::max(r, std::abs(v));
  return r;
}

// One output row: t, q, v, T, U, T + U, outputs, λ, max|C|, max|Ċ|. Buffers are sized once;
// one forward() gives λ together with C and Ċ.
class RowWriter {
 public:
  explicit RowWriter(const CompiledModel& cm)
      : obs_(cm.observables.num_outputs()),
        qdot_(cm.nq),
        a_(cm.nv),
        lambda_(cm.m),
        C_(cm.m),
        Cdot_(cm.m) {}

  void append(Dynamics& dyn, double t, const double* q, const double* v, Trajectory& traj) {
    const CompiledModel& cm = dyn.model();
    std::vector<double>& d = traj.data;
    d.push_back(t);
    d.insert(d.end(), q, q + cm.nq);
    d.insert(d.end(), v, v + cm.nv);
    dyn.observe(t, q, v, obs_.data());
    d.insert(d.end(), {obs_[0], obs_[1], obs_[0] + obs_[1]});
    const auto reactions = obs_.end() - static_cast<long>(cm.reaction_names.size());
    d.insert(d.end(), obs_.begin() + 2, reactions);
    if (cm.m > 0) {
      dyn.forward(t, q, v, qdot_.data(), a_.data(), lambda_.data());
      dyn.last_constraints(C_.data(), Cdot_.data());
      d.insert(d.end(), lambda_.begin(), lambda_.end());
      d.push_back(max_abs(C_));
      d.push_back(max_abs(Cdot_));
      for (size_t r = 0; r < cm.reaction_names.size(); ++r)
        d.push_back(lambda_[cm.reaction_constraints[r]] * reactions[static_cast<long>(r)]);
    }
  }

 private:
  std::vector<double> obs_, qdot_, a_, lambda_, C_, Cdot_;
};

// Initial state: check C = 0 and Ċ = 0, project if needed (docs/theory.md §4.3) and say what moved.
void make_consistent(Dynamics& dyn, const SimulationOptions& opt, std::vector<double>& q,
                     std::vector<double>& v, Trajectory& traj) {
  const CompiledModel& cm = dyn.model();
  if (cm.m == 0) return;
  if (!opt.project_initial) {
    std::vector<double> C(cm.m), Cdot(cm.m);
    dyn.constraints(opt.t0, q.data(), v.data(), C.data(), Cdot.data());
    const double err = max_abs(C), rate_err = max_abs(Cdot);
    if (err <= opt.projection_tol && rate_err <= opt.projection_tol) return;
    throw SimulationError(opt.t0,
                          fmt::format("the initial state is inconsistent: max |C| = {:.3g}, "
                                      "max |Ċ| = {:.3g}",
                                      err, rate_err));
  }
  const InitialConsistency ic =
      make_initial_state_consistent(dyn, opt.t0, q, v, opt.projection_tol);
  if (!ic.consistent)
    throw SimulationError(
        opt.t0,
        fmt::format("the initial state cannot be made consistent: after projection max "
                    "|C| = {:.3g}, max |Ċ| = {:.3g} (at the start {:.3g} and {:.3g}){}",
                    max_abs(ic.C), max_abs(ic.Cdot), max_abs(ic.C0), max_abs(ic.Cdot0),
                    ic.blocked_by_fixed ? "; the coordinates marked fixed stand in the way" : ""));
  if (!ic.was_consistent) traj.notes.push_back(ic.note());
}

// The state the integrator last asked about, kept so that a failure inside the integrator (too
// much work, step size too small, convergence) can say where it happened.
struct LastEvaluation {
  double t = 0.0;
  std::vector<double> q, v, a;
  bool valid = false;
  // set while the dynamics run: a failure there already names the state in its message
  bool reported = false;

  void record(double time, const double* qq, const double* vv, const double* aa) {
    t = time;
    std::copy(qq, qq + q.size(), q.begin());
    std::copy(vv, vv + v.size(), v.begin());
    std::copy(aa, aa + a.size(), a.begin());
    valid = true;
  }

  // "last evaluated state at t = …: x = …, x_dot = …; largest |values|: x_ddot = …" — every q and
  // v for small models, the three entries of largest magnitude among q, v and a otherwise.
  std::string describe(const CompiledModel& cm) const {
    std::vector<std::pair<std::string, double>> all;
    for (size_t i = 0; i < cm.nq; ++i) all.emplace_back(cm.coordinate_names[i], q[i]);
    for (size_t i = 0; i < cm.nv; ++i) all.emplace_back(cm.velocity_names[i], v[i]);
    for (size_t i = 0; i < cm.nv; ++i)  // x_dot → x_ddot; body.wx → body.wx_dot
      all.emplace_back(
          i < cm.plain ? cm.coordinate_names[i] + "_ddot" : cm.velocity_names[i] + "_dot", a[i]);
    auto list = [](auto first, auto last) {
      std::string s;
      for (auto it = first; it != last; ++it)
        s += fmt::format("{}{} = {:.6g}", s.empty() ? "" : ", ", it->first, it->second);
      return s;
    };
    std::string text = fmt::format("last evaluated state at t = {:.17g}", t);
    if (cm.nq <= 4)
      text += ": " + list(all.begin(), all.begin() + static_cast<long>(cm.nq + cm.nv));
    auto magnitude = [](const std::pair<std::string, double>& e) {
      return std::isfinite(e.second) ? std::abs(e.second) : HUGE_VAL;
    };
    const size_t shown = std::min<size_t>(3, all.size());
    std::partial_sort(all.begin(), all.begin() + static_cast<long>(shown), all.end(),
                      [&](const auto& x, const auto& y) { return magnitude(x) > magnitude(y); });
    return text + "; largest values: " + list(all.begin(), all.begin() + static_cast<long>(shown));
  }
};

}  // namespace

Trajectory simulate(Dynamics& dyn, const SimulationOptions& opt, std::vector<double> q0,
                    std::vector<double> v0) {
  const CompiledModel& cm = dyn.model();
  const size_t nq = cm.nq, nv = cm.nv, n = nq + nv, m = cm.m;
  Trajectory traj;
  traj.columns = trajectory_columns(cm);
  if (q0.size() != nq || v0.size() != nv)
    throw std::invalid_argument(
        fmt::format("simulate: expected {} positions and {} velocities, "
                    "got {} and {}",
                    nq, nv, q0.size(), v0.size()));
  std::vector<double> C(m), Cdot(m), lambda(m);
  const std::vector<bool> none_fixed(nq, false);  // drift projection may move every coordinate
  RowWriter rows(cm);
  const bool dae = opt.integrator.method == "ida";
  LastEvaluation last;
  last.q.resize(nq);
  last.v.resize(nv);
  last.a.resize(nv);
  // Drift correction (docs/theory.md §4.3, §4.4): free bodies' R back onto SO(3), then the
  // constraints (which may involve R) onto C = 0, Ċ = 0 when max |C| or max |Ċ| exceeds
  // `allowed`; true when the state moved.
  const auto correct_drift = [&](double t, double* yy, double allowed) {
    const double drift =
        orthonormalize_rotations(cm, yy, opt.project ? opt.projection_tol : HUGE_VAL);
    traj.rotation_drift = std::max(traj.rotation_drift, drift);
    if (!opt.project) return false;
    bool moved = drift > opt.projection_tol;
    if (m > 0) {
      dyn.constraints(t, yy, yy + nq, C.data(), Cdot.data());
      if (max_abs(C) > allowed || max_abs(Cdot) > allowed) {
        dyn.project(t, yy, yy + nq, none_fixed, 1e-13);
        moved = true;
      }
    }
    return moved;
  };
  // ODE methods correct their own state after every internal step (the step hook); IDA restarts
  // at samples instead (StateChanged below).
  // docs/theory.md §4.3, "Projecting when the drift matters": between samples only a drift
  // the error control could resolve is removed; samples are corrected to projection_tol.
  const double step_drift_tol = step_drift_tolerance(opt);
  IntegratorOptions integrator = opt.integrator;
  if (!dae)
    integrator.after_step = [&](double t, double* yy) {
      return correct_drift(t, yy, step_drift_tol);
    };
  // At each output sample: check the state is finite, correct the drift (the sample of an ODE
  // method is its dense output, corrected for the row only), record the row, honour interruption.
  Observer observer = [&](double t, double* yy, double* yp) {
    ObserverAction action = ObserverAction::Continue;
    for (size_t i = 0; i < n; ++i)
      if (!std::isfinite(yy[i])) {
        last.reported = true;
        throw SimulationError(
            t, fmt::format("the state is not finite ({} = {})",
                           i < nq ? cm.coordinate_names[i] : cm.velocity_names[i - nq], yy[i]));
      }
    if (correct_drift(t, yy, opt.projection_tol) &&
        dae) {  // keep (λ, y') consistent with the projected state
      dyn.forward(t, yy, yy + nq, yp, yp + nq, yy + n);
      std::fill(yp + n, yp + n + m, 0.0);
      action = ObserverAction::StateChanged;
    }
    rows.append(dyn, t, yy, yy + nq, traj);
    if (opt.progress) opt.progress(t);
    if (opt.interrupt != nullptr && opt.interrupt->load()) {
      traj.status = Trajectory::Status::Interrupted;
      traj.message = fmt::format("interrupted at t = {:.6g}", t);
      return ObserverAction::Stop;
    }
    return action;
  };
  try {
    make_consistent(dyn, opt, q0, v0, traj);
    if (dae) {
      // Index-1 DAE in (q, v, λ) for IDA, started from the forward-dynamics solution.
      std::vector<double> y(n + m), yp(n + m, 0.0);
      std::copy(q0.begin(), q0.end(), y.begin());
      std::copy(v0.begin(), v0.end(), y.begin() + static_cast<long>(nq));
      dyn.forward(opt.t0, q0.data(), v0.data(), yp.data(), yp.data() + nq, y.data() + n);
      DaeProblem problem;
      problem.size = n + m;
      problem.differential.assign(n + m, true);
      std::fill(problem.differential.begin() + static_cast<long>(n), problem.differential.end(),
                false);
      problem.residual = [&dyn, n, nq, &last](double t, const double* yy, const double* ypp,
                                              double* r) {
        last.reported = true;
        dyn.dae_residual(t, yy, yy + nq, ypp, ypp + nq, yy + n, r);
        last.reported = false;
        last.record(t, yy, yy + nq, ypp + nq);
      };
      traj.stats =
          integrate_dae(problem, integrator, opt.t0, y, yp, opt.t_end, opt.output_step, observer);
    } else {
      std::vector<double> y(n);
      std::copy(q0.begin(), q0.end(), y.begin());
      std::copy(v0.begin(), v0.end(), y.begin() + static_cast<long>(nq));
      OdeProblem ode;
      ode.size = n;
      ode.jacobian = opt.jacobian;
      ode.rhs = [&dyn, nq, &lambda, &last](double t, const double* yy, double* yd) {
        last.reported = true;
        dyn.forward(t, yy, yy + nq, yd, yd + nq, lambda.data());
        last.reported = false;
        last.record(t, yy, yy + nq, yd + nq);
      };
      traj.stats = integrate(ode, integrator, opt.t0, y, opt.t_end, opt.output_step, observer);
    }
  } catch (const SimulationError& e) {
    if (const auto* failure = dynamic_cast<const IntegrationFailure*>(&e))
      traj.stats = failure->stats();  // the work done until the failure (issue 25 item 10)
    traj.status = Trajectory::Status::Failed;
    traj.message = e.what();
    if (last.valid && !last.reported) traj.message += "; " + last.describe(cm);
    traj.failure_time = e.time();
  }
  return traj;
}

}  // namespace lagrange
