#pragma once
// Runs an integrator's walk over the output grid and, when it fails, rethrows the failure as an
// IntegrationFailure carrying the integrator's statistics so far.

#include "lagrange/integration_failure.hpp"

namespace lagrange::integration {

/// walk(); a SimulationError from it becomes IntegrationFailure(e, stats()) (empty statistics
/// when stats() itself fails, so the original error is never lost).
template <class Walk, class Stats>
void keeping_stats(Walk&& walk, Stats&& stats) {
  try {
    walk();
  } catch (const IntegrationFailure&) {
    throw;
  } catch (const SimulationError& e) {
    IntegratorStats so_far;
    try {
      so_far = stats();
    } catch (...) {
    }
    throw IntegrationFailure(e, so_far);
  }
}

}  // namespace lagrange::integration
