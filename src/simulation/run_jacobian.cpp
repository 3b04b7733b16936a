// The exact Jacobian a run integrates on, built for the workspace it evaluates
// (include/lagrange/simulation.hpp, run_jacobian).

#include <fmt/format.h>

#include <stdexcept>

#include "lagrange/error.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

bool uses_jacobian(const std::string& method) {
  return method == "cvode:jacobian" || method == "ida:jacobian" || method == "auto";
}

namespace {

/// `build()` from the source for a run with `method`; `required`: errors name the method, else
/// (auto) an empty result stands for "none".
template <class Jacobian, class Build>
Jacobian from_source(const std::string& method, bool required, double t0, Build build) {
  try {
    return build();
  } catch (const std::invalid_argument& e) {
    if (required) throw std::invalid_argument(fmt::format("{}: {}", method, e.what()));
  } catch (const std::runtime_error& e) {  // e.g. a singular KKT matrix at the start
    if (required)
      throw SimulationError(
          t0, fmt::format("{}: the exact Jacobian at the initial state: {}", method, e.what()));
  }
  return {};
}

[[noreturn]] void throw_no_source(const std::string& method, const char* field) {
  throw std::invalid_argument(
      fmt::format("{} needs the exact Jacobian of the model ({} or "
                  "jacobian_source)",
                  method, field));
}

}  // namespace

OdeJacobian run_jacobian(Dynamics& dynamics, const SimulationOptions& options, double t0,
                         const std::vector<double>& y0) {
  const std::string& method = options.integrator.method;
  if (method != "cvode:jacobian" && method != "auto") return {};
  if (options.jacobian.values) return options.jacobian;
  const bool required = method == "cvode:jacobian";
  if (!options.jacobian_source.ode) {
    if (required) throw_no_source(method, "SimulationOptions::jacobian");
    return {};
  }
  // auto without a Jacobian: DOP853 throughout
  return from_source<OdeJacobian>(method, required, t0,
                                  [&] { return options.jacobian_source.ode(dynamics, t0, y0); });
}

DaeJacobian run_dae_jacobian(Dynamics& dynamics, const SimulationOptions& options, double t0,
                             const std::vector<double>& y0) {
  const std::string& method = options.integrator.method;
  if (method != "ida:jacobian") return {};
  if (!options.jacobian_source.dae) throw_no_source(method, "SimulationOptions");
  return from_source<DaeJacobian>(method, true, t0,
                                  [&] { return options.jacobian_source.dae(dynamics, t0, y0); });
}

}  // namespace lagrange
