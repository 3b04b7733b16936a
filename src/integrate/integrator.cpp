// Front-end of include/lagrange/integrator.hpp: validates inputs and dispatches on the method.

#include "lagrange/integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrate/erk_tables.hpp"
#include "integrate/methods.hpp"
#include "integrate/output_grid.hpp"
#include "integrate/walk_grid.hpp"
#include "lagrange/integration_failure.hpp"

namespace lagrange {

namespace integration {

void validate_options(const IntegratorOptions& options) {
  if (!std::isfinite(options.rtol) || !std::isfinite(options.atol) || options.rtol < 0.0 ||
      options.atol < 0.0 || options.rtol + options.atol <= 0.0) {
    throw std::invalid_argument(fmt::format(
        "integrator: expected rtol >= 0, atol >= 0, not both 0, got rtol = {}, atol = {}",
        options.rtol, options.atol));
  }
  if (!std::isfinite(options.step) || options.step < 0.0) {
    throw std::invalid_argument(
        fmt::format("integrator: expected step >= 0 (0 = output step / 10), got {}", options.step));
  }
  if (options.max_steps <= 0) {
    throw std::invalid_argument(
        fmt::format("integrator: expected max_steps > 0, got {}", options.max_steps));
  }
}

}  // namespace integration

namespace {

/// Throws std::invalid_argument unless a state vector has the problem's (non-zero) size.
void validate_size(size_t size, size_t got, const char* what) {
  if (size == 0) throw std::invalid_argument("integrator: expected a problem size > 0, got 0");
  if (got != size) {
    throw std::invalid_argument(
        fmt::format("integrator: {} has the wrong size, expected {}, got {}", what, size, got));
  }
}

/// `auto` that began explicit: DOP853 until its stiffness test concludes, then cvode:jacobian
/// from the sample it stopped at (docs/theory.md §5.6, "Noticing stiffness during the run").
IntegratorStats integrate_switching(const OdeProblem& problem, const IntegratorOptions& options,
                                    const integration::OutputGrid& grid, std::vector<double>& y,
                                    const Observer& observer) {
  using integration::operator+;
  integration::StiffHandover handover;
  IntegratorStats stats =
      integration::integrate_dop853(problem, options, grid, y, observer, &handover);
  stats.method = "dop853";
  if (!handover.stiff) return stats;
  IntegratorOptions implicit = options;
  implicit.method = "cvode:jacobian";
  bool first = true;  // the sample the handover starts from is in the trajectory already
  const Observer rest = [&](double t, double* yy, double* yp) {
    if (first) {
      first = false;
      return ObserverAction::Continue;
    }
    return observer ? observer(t, yy, yp) : ObserverAction::Continue;
  };
  const integration::OutputGrid tail = grid.from(handover.sample);
  const std::string method =
      fmt::format("dop853, stiff at t = {:.6g}: cvode:jacobian from t = {:.6g}", handover.detected,
                  tail.time(0));
  try {
    y = handover.y;
    stats = stats + integration::integrate_cvode(problem, implicit, tail, y, rest);
  } catch (const IntegrationFailure& e) {
    IntegratorStats so_far = stats + e.stats();
    so_far.method = method;
    throw IntegrationFailure(e, so_far);
  }
  stats.method = method;
  return stats;
}

}  // namespace

IntegratorStats integrate(const OdeProblem& problem, const IntegratorOptions& given, double t0,
                          std::vector<double> y0, double t_end, double dt,
                          const Observer& observer) {
  IntegratorOptions options = given;
  bool switching = false;  // auto that starts explicit may turn implicit during the run
  if (options.method == "auto") {
    validate_size(problem.size, y0.size(), "y0");
    options.method = choose_ode_method(problem.jacobian, t0, y0, dt);
    switching = options.method == "dop853" && problem.jacobian.values && options.step == 0.0;
  }
  const std::string& method = options.method;
  const std::vector<std::string>& known = integrator_methods();
  if (method == "ida" || std::find(known.begin(), known.end(), method) == known.end()) {
    throw std::invalid_argument(fmt::format(
        "integrator: unknown ODE method '{}', expected one of {}{}", method,
        integrator_method_list(), method == "ida" ? " (ida is for DAEs: use integrate_dae)" : ""));
  }
  integration::validate_options(options);
  validate_size(problem.size, y0.size(), "y0");
  if (!problem.rhs) throw std::invalid_argument("integrator: the ODE has no right-hand side");
  const integration::OutputGrid grid(t0, t_end, dt);
  IntegratorStats stats;
  if (method == "cvode:jacobian" && !problem.jacobian.values)
    throw std::invalid_argument(
        "integrator: cvode:jacobian needs the problem's exact Jacobian (OdeProblem::jacobian)");
  if (method == "cvode" || method == "cvode:jacobian") {
    stats = integration::integrate_cvode(problem, options, grid, y0, observer);
  } else if (switching) {
    stats = integrate_switching(problem, options, grid, y0, observer);
  } else if (method == "dop853") {
    stats = integration::integrate_dop853(problem, options, grid, y0, observer);
  } else if (method == "rk4") {
    stats = integration::integrate_rk4(problem, options, grid, y0, observer);
  } else if (method == "midpoint") {
    stats = integration::integrate_midpoint(problem, options, grid, y0, observer);
  } else {
    stats = integration::integrate_arkode(problem, options, grid, y0, observer);
  }
  if (method == "arkode")
    stats.method = std::string("arkode:") + integration::default_erk_table(options.rtol).name;
  else if (!switching)
    stats.method = method;
  return stats;
}

IntegratorStats integrate_dae(const DaeProblem& problem, const IntegratorOptions& options,
                              double t0, std::vector<double> y0, std::vector<double> yp0,
                              double t_end, double dt, const Observer& observer) {
  if (options.method != "ida") {
    throw std::invalid_argument(
        fmt::format("integrator: unknown DAE method '{}', expected ida", options.method));
  }
  if (options.after_step)
    throw std::invalid_argument("integrator: ida takes no step hook (it restarts at samples)");
  integration::validate_options(options);
  validate_size(problem.size, y0.size(), "y0");
  validate_size(problem.size, yp0.size(), "yp0");
  validate_size(problem.size, problem.differential.size(), "differential");
  if (!problem.residual) throw std::invalid_argument("integrator: the DAE has no residual");
  const integration::OutputGrid grid(t0, t_end, dt);
  IntegratorStats stats = integration::integrate_ida(problem, options, grid, y0, yp0, observer);
  stats.method = "ida";
  return stats;
}

}  // namespace lagrange
