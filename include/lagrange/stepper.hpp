#pragma once
// A controller in the loop: advance a model's dynamics to t + Δt with new input values, keeping
// the integrator's state between calls (the stepping interface of KiteModels.jl's next_step! and
// MuJoCo's mj_step).

#include <memory>
#include <string>
#include <vector>

#include "lagrange/dynamics.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

/// Steps one model from (options.t0, q0, v0) by calls to step(dt). With DOP853 (the default) one
/// integration runs across all calls: while no caller has set an input, it steps across the
/// targets and samples its continuous extension exactly as simulate() does, so the states at
/// t0 + k·Δt equal simulate()'s rows with output_step Δt bit for bit (options.t_end is where its
/// last step lands, as in simulate()); once inputs are set, its steps land on each target so that
/// a new value takes effect there, and the step size carries over. Other methods run simulate()
/// from the current state for each call (they agree with one run to the integrator's tolerance).
/// Drift correction (projection onto C = 0, Ċ = 0, rotations onto SO(3)) and the checks of each
/// state (docs/theory.md §8.2) are simulate()'s. cvode:jacobian and auto integrate on the exact
/// Jacobian that options.jacobian_source builds once for the Stepper's own workspace.
class Stepper {
 public:
  /// Takes the workspace (its parameters, Baumgarte rate and evaluation as the caller set them)
  /// and makes (q0, v0) consistent as simulate() does; throws SimulationError at t0 when it
  /// cannot, std::invalid_argument for wrong sizes or options.
  Stepper(Dynamics dynamics, const SimulationOptions& options, std::vector<double> q0,
          std::vector<double> v0);
  ~Stepper();
  Stepper(Stepper&&) noexcept;
  Stepper& operator=(Stepper&&) noexcept;

  /// The time of the state (t0, then the target of the last successful step).
  double time() const;
  /// The state at time(): q (nq) then v (nv), drift-corrected as a simulate() row.
  const std::vector<double>& state() const;
  /// Names of the model's external inputs (declared `external: true`), the ones a caller sets.
  const std::vector<std::string>& external_inputs() const;
  /// Holds external input `name` at `value` from time() on (until set again); before the first
  /// call an input follows its declared value. std::invalid_argument for an unknown name or one
  /// not declared external.
  void set_input(const std::string& name, double value);
  /// A law for the external inputs (in the order of external_inputs()), evaluated with the state
  /// at every evaluation of the dynamics from time() on, instead of held values; empty: held
  /// values again. For a feedback law that is continuous in time.
  void set_input_law(Dynamics::InputLaw law);
  /// Advances to time() + dt (dt > 0). Throws SimulationError (with the time it failed at) when
  /// the integration fails; then time() and state() are still those before the call, and the
  /// next call starts the integrator afresh from them. step(), set_input() and set_input_law()
  /// called while a step runs (from the input law, or another thread) throw std::runtime_error
  /// "stepper in use" and change nothing.
  void step(double dt);
  /// The states so far as simulate() rows (t0 and every step's target), with the integrator's
  /// statistics.
  const Trajectory& record() const;
  /// The workspace the steps evaluate.
  Dynamics& dynamics();

 private:
  struct State;
  std::unique_ptr<State> s_;
};

}  // namespace lagrange
