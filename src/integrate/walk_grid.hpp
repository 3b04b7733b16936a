#pragma once
// The observer loop shared by every method: sample t0, then advance to each t_k and sample it.

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

/// Component-wise sum, used to carry counters across integrator re-initialisations.
inline IntegratorStats operator+(const IntegratorStats& a, const IntegratorStats& b) {
  return {a.steps + b.steps, a.rhs_evals + b.rhs_evals, a.failed_steps + b.failed_steps};
}

}  // namespace lagrange::integration
