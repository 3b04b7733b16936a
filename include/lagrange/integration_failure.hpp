#pragma once
// A failed integration with the work it did (issue 25 item 10): the statistics of a run that
// ends in SimulationError, so a failed run's sidecar reports its steps and rhs evaluations.

#include "lagrange/error.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {

/// The SimulationError of integrate() or integrate_dae(), with the statistics up to the failure.
class IntegrationFailure : public SimulationError {
 public:
  IntegrationFailure(const SimulationError& e, IntegratorStats stats)
      : SimulationError(e), stats_(std::move(stats)) {}
  const IntegratorStats& stats() const { return stats_; }

 private:
  IntegratorStats stats_;
};

}  // namespace lagrange
