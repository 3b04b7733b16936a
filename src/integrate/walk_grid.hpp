#pragma once
// The observer loops: walk_grid (sample t0, then advance to each t_k and sample it; IDA) and
// walk_dense (step freely and sample the dense output between steps; ARKODE, CVODE, fixed-step).

#include <algorithm>
#include <vector>

#include "integrate/output_grid.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange::integration {

/// Walks the grid: observe t0; for k = 1..K call advance(t_k) (which must leave y, yp at t_k)
/// and observe. StateChanged calls restart(t_k) before going on; Stop ends the walk.
template <class Advance, class Restart>
void walk_grid(const OutputGrid& grid, const Observer& observer, double* y, double* yp,
               Advance&& advance, Restart&& restart) {
  for (size_t k = 0;; ++k) {
    const double t = grid.time(k);
    if (k > 0) advance(t);
    const ObserverAction action = observer ? observer(t, y, yp) : ObserverAction::Continue;
    if (action == ObserverAction::Stop || k == grid.intervals()) return;
    if (action == ObserverAction::StateChanged) restart(t);
  }
}

/// Walks the grid with dense output: observe t0; then repeatedly step(t_next) (one internal step
/// of y toward the next sample t_next, returning the time reached; the last one lands exactly on
/// t_end), observe every sample t_k up to that time from interpolate(t_k, out) (y itself at the
/// step's end), then offer y to `after_step` (after every step, or with `hook_at_samples_only`
/// only after steps that reached a sample: for methods whose restart is expensive). A sample's
/// StateChanged discards the rest of the step: y becomes the observed state and
/// restart(t_k, false) starts afresh from it; a hook that changed y calls restart(t, true) (a
/// small correction: the method may keep its step size). Stop ends the walk.
template <class Step, class Interpolate, class Restart>
void walk_dense(const OutputGrid& grid, const Observer& observer, const StepHook& after_step,
                bool hook_at_samples_only, std::vector<double>& y, Step&& step,
                Interpolate&& interpolate, Restart&& restart) {
  std::vector<double> sample = y;
  const auto observe = [&](double t) {
    return observer ? observer(t, sample.data(), nullptr) : ObserverAction::Continue;
  };
  const size_t last = grid.intervals();
  ObserverAction action = observe(grid.time(0));
  if (action == ObserverAction::Stop || last == 0) return;
  if (action == ObserverAction::StateChanged) {
    y = sample;
    restart(grid.time(0), false);
  }
  for (size_t k = 1;;) {
    const double t = step(grid.time(k));
    const size_t k_before = k;
    bool restarted = false;
    while (k <= last && grid.time(k) <= t) {
      const double t_k = grid.time(k);
      if (t_k == t) {
        sample = y;
      } else {
        interpolate(t_k, sample.data());
      }
      action = observe(t_k);
      if (action == ObserverAction::Stop || k == last) return;
      ++k;
      if (action == ObserverAction::StateChanged) {
        y = sample;
        restart(t_k, false);
        restarted = true;
        break;
      }
    }
    const bool hook = after_step && (!hook_at_samples_only || k != k_before);
    if (!restarted && hook && after_step(t, y.data())) restart(t, true);
  }
}

/// Component-wise sum, used to carry counters across integrator re-initialisations.
inline IntegratorStats operator+(const IntegratorStats& a, const IntegratorStats& b) {
  return {a.steps + b.steps, a.rhs_evals + b.rhs_evals, a.failed_steps + b.failed_steps,
          b.method.empty() ? a.method : b.method};
}

}  // namespace lagrange::integration
