#include "lagrange/simulation.hpp"

namespace lagrange {

// docs/theory.md §4.3, "Choosing α".
double baumgarte_rate(const Stabilization& stabilization, const std::string& method) {
  if (stabilization.alpha) return *stabilization.alpha;
  const bool projects_after_steps = method != "cvode" && method != "ida";
  return stabilization.project && projects_after_steps ? 0.0 : kDefaultBaumgarte;
}

}  // namespace lagrange
