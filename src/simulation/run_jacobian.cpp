// The exact Jacobian a run integrates on, built for the workspace it evaluates
// (include/lagrange/simulation.hpp, run_jacobian).

#include <fmt/format.h>

#include <stdexcept>

#include "lagrange/error.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

bool uses_jacobian(const std::string& method) {
  return method == "cvode:jacobian" || method == "auto";
}

OdeJacobian run_jacobian(Dynamics& dynamics, const SimulationOptions& options, double t0,
                         const std::vector<double>& y0) {
  const std::string& method = options.integrator.method;
  if (!uses_jacobian(method)) return {};
  if (options.jacobian.values) return options.jacobian;
  const bool required = method == "cvode:jacobian";
  if (!options.jacobian_source) {
    if (required)
      throw std::invalid_argument(
          "cvode:jacobian needs the exact Jacobian of the model (SimulationOptions::jacobian or "
          "jacobian_source)");
    return {};
  }
  try {
    return options.jacobian_source(dynamics, t0, y0);
  } catch (const std::invalid_argument& e) {
    if (required) throw std::invalid_argument(fmt::format("cvode:jacobian: {}", e.what()));
  } catch (const std::runtime_error& e) {  // e.g. a singular KKT matrix at the start
    if (required)
      throw SimulationError(t0, fmt::format("cvode:jacobian: the exact Jacobian at the initial "
                                            "state: {}",
                                            e.what()));
  }
  return {};  // auto without a Jacobian: DOP853 throughout
}

}  // namespace lagrange
