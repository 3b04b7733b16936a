#include <algorithm>

#include "lagrange/simulation.hpp"
#include "simulation/drift_correction.hpp"

namespace lagrange {

// docs/theory.md §4.3, "Choosing α".
double baumgarte_rate(const Stabilization& stabilization, const std::string& method) {
  if (stabilization.alpha) return *stabilization.alpha;
  return stabilization.project && !corrects_only_at_samples(method) ? 0.0 : kDefaultBaumgarte;
}

// docs/theory.md §4.3, "Projecting when the drift matters".
double step_drift_tolerance(const SimulationOptions& options) {
  if (options.step_drift_tol > 0.0) return options.step_drift_tol;
  return std::max(options.projection_tol, options.integrator.atol);
}

}  // namespace lagrange
