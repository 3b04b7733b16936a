#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

#include "lagrange/error.hpp"
#include "lagrange/integration_failure.hpp"
#include "lagrange/simulation.hpp"
#include "lagrange/stop_conditions.hpp"
#include "simulation/drift_correction.hpp"
#include "simulation/row_writer.hpp"
#include "simulation/sample_checks.hpp"
#include "simulation/start_state.hpp"

namespace lagrange {

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

// Thrown from the dynamics when the run's interrupt flag is set; caught by simulate().
struct Interrupted {};

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

// docs/model-language.md, "Stop conditions": g of every condition at each output sample; one
// that was not positive at the previous sample and is now fired in between. Its first positive
// time is located by re-integrating from the previous sample with DOP853 at the run's tolerances
// to times chosen by the Illinois variant of regula falsi on g, until the bracket is below
// 1e-12 (1 + |t|).
class StopWatch {
 public:
  /// State y (q, v) at t: integrated from the previous sample.
  using Advance =
      std::function<std::vector<double>(double t_from, const std::vector<double>& y, double t)>;
  /// g at a state: the row's conditions.
  using Evaluate = std::function<void(double t, const double* y, double* g)>;

  StopWatch(size_t conditions, size_t n) : g_prev_(conditions), g_(conditions), y_prev_(n) {}

  /// At a sample with condition values `g` (from its row): true when a condition fired since the
  /// previous sample; then `which`, `when` and `state` are the earliest located crossing.
  bool fired(double t, const double* y, const double* g, const Evaluate& evaluate,
             const Advance& advance) {
    std::copy(g, g + g_.size(), g_.begin());
    bool fired = false;
    if (started_) {
      when = HUGE_VAL;
      for (size_t i = 0; i < g_.size(); ++i) {
        if (!(g_prev_[i] <= 0 && g_[i] > 0)) continue;
        auto [t_i, y_i] = locate(i, t, y, evaluate, advance);
        if (t_i < when) {
          when = t_i, which = i, state = std::move(y_i);
          fired = true;
        }
      }
    }
    started_ = true;
    t_prev_ = t;
    g_prev_ = g_;
    std::copy(y, y + y_prev_.size(), y_prev_.begin());
    return fired;
  }

  /// The first condition that fired since the previous sample by the values `g`, or size().
  size_t first_fired(const double* g) const {
    for (size_t i = 0; started_ && i < g_.size(); ++i)
      if (g_prev_[i] <= 0 && g[i] > 0) return i;
    return g_.size();
  }

  size_t which = 0;
  double when = 0.0;
  std::vector<double> state;

 private:
  std::pair<double, std::vector<double>> locate(size_t i, double t, const double* y,
                                                const Evaluate& evaluate, const Advance& advance) {
    double a = t_prev_, ga = g_prev_[i], b = t, gb = g_[i];
    std::vector<double> yb(y, y + y_prev_.size()), g(g_.size());
    int side = 0;  // Illinois: halve the weight of an end kept twice in a row
    for (int it = 0; it < 100 && b - a > 1e-12 * (1 + std::abs(b)); ++it) {
      double c = ga == gb ? (a + b) / 2 : b - gb * (b - a) / (gb - ga);
      if (!(c > a && c < b)) c = (a + b) / 2;
      std::vector<double> yc = advance(t_prev_, y_prev_, c);
      evaluate(c, yc.data(), g.data());
      if (g[i] > 0) {
        b = c, gb = g[i], yb = std::move(yc);
        if (side == 1) ga /= 2;
        side = 1;
      } else {
        a = c, ga = g[i];
        if (side == -1) gb /= 2;
        side = -1;
      }
    }
    return {b, yb};
  }

  bool started_ = false;
  double t_prev_ = 0.0;
  std::vector<double> g_prev_, g_, y_prev_;
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
  std::vector<double> lambda(m);
  RowWriter rows(cm);
  const bool dae = opt.integrator.method == "ida" || opt.integrator.method == "ida:jacobian";
  LastEvaluation last;
  last.q.resize(nq);
  last.v.resize(nv);
  last.a.resize(nv);
  // Drift correction (docs/theory.md §4.3, §4.4): free bodies' R back onto SO(3), then the
  // constraints (which may involve R) onto C = 0, Ċ = 0; true when the state moved. At samples to
  // projection_tol, after internal steps to step_drift_tolerance() (docs/theory.md §4.3).
  DriftCorrection drift(dyn, opt);
  const auto correct_drift = [&](double t, double* yy) {
    const bool moved = drift(t, yy);
    traj.rotation_drift = drift.largest_rotation_drift();
    return moved;
  };
  const auto correct_step_drift = [&](double t, double* yy) {
    const bool moved = drift.after_step(t, yy);
    traj.rotation_drift = drift.largest_rotation_drift();
    return moved;
  };
  // ODE methods correct their own state after every internal step (the step hook); IDA restarts
  // at samples instead, when the drift there exceeds the step tolerance (StateChanged below).
  IntegratorOptions integrator = opt.integrator;
  if (!dae) integrator.after_step = correct_step_drift;
  OdeProblem ode;
  ode.size = n;
  // Ctrl-C between samples (issue 25 item 9): the next evaluation of the dynamics ends the run
  // with the rows so far, as at a sample.
  const auto poll_interrupt = [&opt] {
    if (opt.interrupt != nullptr && opt.interrupt->load(std::memory_order_relaxed))
      throw Interrupted{};
  };
  ode.rhs = [&dyn, nq, &lambda, &last, &poll_interrupt](double t, const double* yy, double* yd) {
    poll_interrupt();
    last.reported = true;
    dyn.forward(t, yy, yy + nq, yd, yd + nq, lambda.data());
    last.reported = false;
    last.record(t, yy, yy + nq, yd + nq);
  };
  // The model's stop conditions end the run; its elements' domain conditions (cm.fail_when)
  // fail it, both located between samples.
  const StopConditions stop(cm), guards(cm, StopConditions::Kind::Fail);
  StopWatch watch(stop.size(), n), guard_watch(guards.size(), n);
  std::vector<double> stop_row, stop_g(stop.size()), guard_g(guards.size());
  std::vector<bool> stop_was_number(stop.size(), false);  // NaN at every sample: warned after
  const auto values_of = [&](const StopConditions& conditions) -> StopWatch::Evaluate {
    return [&](double t, const double* yy, double* g) {
      stop_row.clear();
      rows.write(dyn, t, yy, yy + nq, stop_row);
      conditions.evaluate(stop_row.data(), dyn.parameters().data(), g);
    };
  };
  const StopWatch::Evaluate stop_values = values_of(stop), guard_values = values_of(guards);
  SampleChecks checks(cm, traj.columns);
  const StopWatch::Advance advance = [&](double t_from, const std::vector<double>& y0,
                                         double t_to) {
    IntegratorOptions refine = opt.integrator;
    refine.method = "dop853";
    refine.step = 0.0;
    refine.after_step = correct_step_drift;
    std::vector<double> y = y0;
    integrate(ode, refine, t_from, y0, t_to, t_to - t_from, [&](double t, double* yy, double*) {
      if (t == t_to) std::copy(yy, yy + n, y.begin());
      return ObserverAction::Continue;
    });
    return y;
  };
  // At each output sample: check the state is finite, correct the drift (the sample of an ODE
  // method is its dense output, corrected for the row only), record the row and check it (the
  // same checks for every method, docs/theory.md §8.2; a row that fails them is dropped), honour
  // interruption.
  Observer observer = [&](double t, double* yy, double* yp) {
    ObserverAction action = ObserverAction::Continue;
    const size_t width = traj.columns.size();
    last.reported = true;  // the sample's checks name their own values
    checks.state(t, yy);
    last.reported = false;
    // IDA's sample is its interpolant, which it does not read back: like an ODE method's dense
    // output it is corrected for the row only, unless the drift exceeds what the error control
    // resolves (docs/theory.md §4.3): then IDA restarts from the projected state, with (λ, y')
    // consistent with it.
    if (dae && correct_step_drift(t, yy)) {
      correct_drift(t, yy);
      dyn.forward(t, yy, yy + nq, yp, yp + nq, yy + n);
      std::fill(yp + n, yp + n + m, 0.0);
      action = ObserverAction::StateChanged;
    } else {
      correct_drift(t, yy);
    }
    try {
      checks.append_row(rows, dyn, t, yy, traj, [&](const double* row) {
        if (guards.empty()) return;
        guards.evaluate(row, dyn.parameters().data(), guard_g.data());
        size_t which = guard_watch.first_fired(guard_g.data());
        double when = t;
        try {
          if (guard_watch.fired(t, yy, guard_g.data(), guard_values, advance))
            which = guard_watch.which, when = guard_watch.when;
        } catch (const SimulationError& e) {
          if (which == guards.size()) throw;
          when = e.time();  // the dynamics give out at the edge of the domain: the crossing
        }
        if (which < guards.size()) {
          const StopSpec& g = guards.spec(which);
          throw SimulationError(
              when, fmt::format("{}: {} became true ({})", g.name, g.text, g.loc.str()));
        }
      });
    } catch (const SimulationError&) {
      last.reported = true;
      throw;
    }
    if (!stop.empty()) {  // the conditions read the row just written
      stop.evaluate(traj.data.data() + traj.data.size() - width, dyn.parameters().data(),
                    stop_g.data());
      for (size_t k = 0; k < stop.size(); ++k)
        if (!std::isnan(stop_g[k])) stop_was_number[k] = true;
      if (watch.fired(t, yy, stop_g.data(), stop_values, advance)) {
        traj.data.resize(traj.data.size() - width);  // the sample lies past the stop
        const double* y = watch.state.data();
        rows.append(dyn, watch.when, y, y + nq, traj);
        traj.stopped_by = stop.spec(watch.which).name;
        traj.stop_time = watch.when;
        if (opt.progress) opt.progress(watch.when);
        return ObserverAction::Stop;
      }
    }
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
      problem.residual = [&dyn, n, nq, &last, &poll_interrupt](double t, const double* yy,
                                                               const double* ypp, double* r) {
        poll_interrupt();
        last.reported = true;
        dyn.dae_residual(t, yy, yy + nq, ypp, ypp + nq, yy + n, r);
        last.reported = false;
        last.record(t, yy, yy + nq, ypp + nq);
      };
      problem.jacobian = run_dae_jacobian(dyn, opt, opt.t0, y);  // on this workspace
      traj.stats =
          integrate_dae(problem, integrator, opt.t0, y, yp, opt.t_end, opt.output_step, observer);
    } else {
      std::vector<double> y(n);
      std::copy(q0.begin(), q0.end(), y.begin());
      std::copy(v0.begin(), v0.end(), y.begin() + static_cast<long>(nq));
      ode.jacobian = run_jacobian(dyn, opt, opt.t0, y);  // on this workspace, from the start
      traj.stats = integrate(ode, integrator, opt.t0, y, opt.t_end, opt.output_step, observer);
    }
  } catch (const Interrupted&) {
    traj.status = Trajectory::Status::Interrupted;
    const size_t rows = traj.rows();
    traj.message = fmt::format("interrupted at t = {:.6g}",
                               rows ? traj.data[(rows - 1) * traj.columns.size()] : opt.t0);
  } catch (const SimulationError& e) {
    if (const auto* failure = dynamic_cast<const IntegrationFailure*>(&e))
      traj.stats = failure->stats();  // the work done until the failure (issue 25 item 10)
    traj.status = Trajectory::Status::Failed;
    traj.message = e.what();
    if (last.valid && !last.reported) traj.message += "; " + last.describe(cm);
    traj.failure_time = e.time();
  }
  // A condition that was NaN at every sample could never fire (issue 37 item 20): said once.
  for (size_t k = 0; k < stop.size() && traj.rows() > 0; ++k)
    if (!stop_was_number[k])
      traj.warnings.push_back(
          fmt::format("stop condition {}: {} was not a number at every sample ({}), so it never "
                      "fired",
                      stop.spec(k).name, stop.spec(k).text, stop.spec(k).loc.str()));
  return traj;
}

}  // namespace lagrange
