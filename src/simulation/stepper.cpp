#include "lagrange/stepper.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrate/dop853.hpp"
#include "integrate/methods.hpp"
#include "integrate/solver_errors.hpp"
#include "integrate/walk_grid.hpp"
#include "lagrange/error.hpp"
#include "simulation/drift_correction.hpp"
#include "simulation/row_writer.hpp"
#include "simulation/sample_checks.hpp"
#include "simulation/start_state.hpp"

namespace lagrange {

// One call that changes the stepper, refusing another while it runs: an input law that calls
// step() or set_input() on its own stepper, or a second thread, would corrupt the integration
// (issue 37 item 8). The refused call changes nothing.
class InUse {
 public:
  explicit InUse(std::atomic<bool>& busy) : busy_(busy) {
    if (busy_.exchange(true))
      throw std::runtime_error(
          "stepper in use: a step of this stepper is running (called from its input law, or "
          "from another thread)");
  }
  InUse(const InUse&) = delete;
  InUse& operator=(const InUse&) = delete;
  ~InUse() { busy_ = false; }

 private:
  std::atomic<bool>& busy_;
};

// The stepper's state lives on the heap: the integrator and the drift correction keep references
// to the workspace, the options, the problem and y.
struct Stepper::State {
  State(Dynamics d, const SimulationOptions& o)
      : dyn(std::move(d)),
        opt(o),
        nq(dyn.model().nq),
        n(dyn.model().nq + dyn.model().nv),
        lambda(dyn.model().m),
        rows(dyn.model()),
        checks(dyn.model(), trajectory_columns(dyn.model())),
        drift(dyn, opt),
        budget(opt.integrator.max_steps) {}

  Dynamics dyn;
  SimulationOptions opt;
  size_t nq, n;
  std::vector<double> y;       // the integrator's state at t_reached
  std::vector<double> sample;  // the state at t (what state() shows)
  std::vector<double> before;  // sample before the current call, restored when it fails
  std::vector<double> lambda;
  double t = 0.0, t_reached = 0.0;
  Trajectory record;
  RowWriter rows;
  SampleChecks checks;
  DriftCorrection drift;
  OdeProblem ode;
  std::unique_ptr<integration::Dop853> dop;  // null: the method restarts at each call
  integration::StepBudget budget;
  bool hook_pending = false;           // the last step's drift correction is still to be applied
  bool lands = false;                  // steps land on each target (a caller has set inputs)
  bool changed = false;                // the inputs changed at t: the integrator restarts there
  bool restart = false;                // a failed call left the integrator behind: start afresh
  double origin = 0.0, spacing = 0.0;  // the targets origin + k·spacing, as simulate()'s grid
  size_t count = 0;
  std::vector<std::string> external_names;
  std::vector<size_t> external_index;  // into input_names
  std::vector<double> held;            // per input: the value set (NaN: not set)
  std::atomic<bool> busy{false};       // a step() is running (its input law may call back)

  // The row of a target as simulate() records its samples: the state checked finite,
  // drift-corrected (the row only), recorded and checked (docs/theory.md §8.2).
  void observe(double time) {
    checks.state(time, sample.data());
    drift(time, sample.data());
    record.rotation_drift = drift.largest_rotation_drift();
    checks.append_row(rows, dyn, time, sample.data(), record);
  }

  // docs/theory.md §8.1, Stepping with a controller in the loop: DOP853 across calls,
  // integrate_dop853's walk (src/integrate/walk_grid.hpp, walk_dense) cut at each target, with
  // the drift correction of a step applied before the next step; after new inputs, a restart from
  // the state at t, and steps that land on the targets.
  void advance_dop853(double target) {
    if (restart || changed) {  // from the state the caller sees, with the dynamics now in force
      y = sample;
      t_reached = t;
      hook_pending = false;
      dop->start(t, !restart);
      restart = changed = false;
    }
    if (target > t_reached) {
      if (lands)
        dop->set_end(target);
      else if (target > dop->end())
        dop->set_end(HUGE_VAL);
    }
    while (t_reached < target) {
      if (hook_pending) {
        hook_pending = false;
        if (drift.after_step(t_reached, y.data())) dop->start(t_reached, true);
      }
      budget.spend(target, t_reached, "dop853", "TOO_MUCH_WORK");
      t_reached = dop->step();
      hook_pending = true;
    }
    if (target == t_reached)
      sample = y;
    else
      dop->interpolate(target, sample.data());
    record.stats = dop->stats();
    record.stats.method = "dop853";
    observe(target);
  }

  // Other methods: one simulate() run from (t, sample) to the target.
  void advance_restarting(double target, double dt) {
    SimulationOptions run = opt;
    run.t0 = t;
    run.t_end = target;
    run.output_step = dt;
    run.progress = nullptr;
    const Trajectory piece =
        simulate(dyn, run, std::vector<double>(sample.begin(), sample.begin() + nq),
                 std::vector<double>(sample.begin() + nq, sample.end()));
    if (piece.status == Trajectory::Status::Failed)
      throw SimulationError(piece.failure_time, piece.message);
    const size_t width = piece.columns.size();
    const auto last = piece.data.end() - static_cast<long>(width);
    std::copy(last + 1, last + 1 + static_cast<long>(n), sample.begin());
    record.data.insert(record.data.end(), last, piece.data.end());
    record.stats = integration::operator+(record.stats, piece.stats);
    record.rotation_drift = std::max(record.rotation_drift, piece.rotation_drift);
    for (const std::string& warning : piece.warnings) {  // once per condition across the calls
      const std::string condition = warning.substr(warning.find(": ") + 2);
      const bool known = std::any_of(
          record.warnings.begin(), record.warnings.end(),
          [&](const std::string& w) { return w.substr(w.find(": ") + 2) == condition; });
      if (!known) record.warnings.push_back(warning);
    }
  }
};

Stepper::Stepper(Dynamics dynamics, const SimulationOptions& options, std::vector<double> q0,
                 std::vector<double> v0)
    : s_(std::make_unique<State>(std::move(dynamics), options)) {
  State& s = *s_;
  const CompiledModel& cm = s.dyn.model();
  if (q0.size() != cm.nq || v0.size() != cm.nv)
    throw std::invalid_argument(
        fmt::format("stepper: expected {} positions and {} velocities, got {} and {}", cm.nq, cm.nv,
                    q0.size(), v0.size()));
  const std::vector<std::string>& known = integrator_methods();
  if (std::find(known.begin(), known.end(), options.integrator.method) == known.end())
    throw std::invalid_argument(fmt::format("stepper: unknown integrator '{}', expected one of {}",
                                            options.integrator.method, integrator_method_list()));
  integration::validate_options(options.integrator);
  for (size_t i = 0; i < cm.k; ++i)
    if (cm.external_inputs[i]) {
      s.external_names.push_back(cm.input_names[i]);
      s.external_index.push_back(i);
    }
  s.held.assign(cm.k, NAN);
  s.record.columns = trajectory_columns(cm);
  make_consistent(s.dyn, s.opt, q0, v0, s.record);
  s.y = q0;
  s.y.insert(s.y.end(), v0.begin(), v0.end());
  s.sample = s.y;
  s.t = s.t_reached = s.origin = options.t0;
  // cvode:jacobian and auto: the exact Jacobian on this workspace, built once for every call
  // (a given one refers to the caller's workspace).
  s.opt.jacobian = {};
  s.opt.jacobian = run_jacobian(s.dyn, s.opt, options.t0, s.y);
  if (options.integrator.method == "dop853") {
    s.ode.size = s.n;
    State* self = &s;
    s.ode.rhs = [self](double t, const double* y, double* ydot) {
      self->dyn.forward(t, y, y + self->nq, ydot, ydot + self->nq, self->lambda.data());
    };
    s.dop = std::make_unique<integration::Dop853>(s.ode, s.opt.integrator, s.y, options.t_end);
    s.dop->start(options.t0, false);
  }
  s.observe(options.t0);
}

Stepper::~Stepper() = default;
Stepper::Stepper(Stepper&&) noexcept = default;
Stepper& Stepper::operator=(Stepper&&) noexcept = default;

double Stepper::time() const {
  return s_->t;
}
const std::vector<double>& Stepper::state() const {
  return s_->sample;
}
const std::vector<std::string>& Stepper::external_inputs() const {
  return s_->external_names;
}
const Trajectory& Stepper::record() const {
  return s_->record;
}
Dynamics& Stepper::dynamics() {
  return s_->dyn;
}

void Stepper::set_input(const std::string& name, double value) {
  State& s = *s_;
  const InUse in_use(s.busy);
  const std::vector<std::string>& names = s.dyn.model().input_names;
  const auto it = std::find(names.begin(), names.end(), name);
  std::string list = s.external_names.empty() ? "none" : "";
  for (const std::string& e : s.external_names) list += (list.empty() ? "" : ", ") + e;
  if (it == names.end() || !s.dyn.model().external_inputs[static_cast<size_t>(it - names.begin())])
    throw std::invalid_argument(fmt::format(
        "stepper: '{}' is not an external input of the model (external inputs: {}); declare it "
        "as `inputs: {{{}: {{value: …, external: true}}}}`",
        name, list, name));
  if (!std::isfinite(value))
    throw std::invalid_argument(fmt::format("stepper: input '{}' = {} is not finite", name, value));
  const size_t i = static_cast<size_t>(it - names.begin());
  if (!(s.held[i] == value)) s.changed = true;  // NaN (never set) compares unequal
  s.held[i] = value;
  s.lands = true;
  s.dyn.hold_input(i, value);
}

void Stepper::set_input_law(Dynamics::InputLaw law) {
  State& s = *s_;
  const InUse in_use(s.busy);
  s.dyn.set_input_law(s.external_index, std::move(law));
  s.changed = true;
}

void Stepper::step(double dt) {
  State& s = *s_;
  const InUse in_use(s.busy);
  if (!std::isfinite(dt) || !(dt > 0.0))
    throw std::invalid_argument(fmt::format("stepper: expected a step dt > 0, got {}", dt));
  if (dt != s.spacing) {
    s.origin = s.t;
    s.spacing = dt;
    s.count = 0;
  }
  double target = s.origin + static_cast<double>(s.count + 1) * dt;
  // simulate()'s last sample is t_end itself
  if (std::abs(target - s.opt.t_end) <= 1e-9 * dt) target = s.opt.t_end;
  const size_t rows = s.record.data.size();
  s.before = s.sample;
  try {
    if (s.dop)
      s.advance_dop853(target);
    else
      s.advance_restarting(target, dt);
  } catch (...) {
    // Back to the state before the call: the integrator starts afresh from it next time.
    s.record.data.resize(rows);
    s.sample = s.before;
    s.y = s.sample;
    s.t_reached = s.t;
    s.hook_pending = false;
    s.restart = s.dop != nullptr;
    throw;
  }
  s.t = target;
  ++s.count;
}

}  // namespace lagrange
