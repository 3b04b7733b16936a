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
  if (options.max_order < 1 || options.max_order > 5) {
    throw std::invalid_argument(
        fmt::format("integrator: expected max_order from 1 to 5 (BDF), got {}", options.max_order));
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

/// The summary of a run under `auto` that switched: the first kShownSwitches switches, then how
/// many more and where the last one went.
std::string switch_summary(const std::vector<std::string>& switches) {
  constexpr size_t kShownSwitches = 4;
  std::string text = "dop853";
  for (size_t i = 0; i < switches.size() && i < kShownSwitches; ++i) text += ", " + switches[i];
  if (switches.size() > kShownSwitches)
    text += fmt::format(", … {} switches in all, the last {}", switches.size(), switches.back());
  return text;
}

/// `auto` that began explicit: DOP853 until its stiffness test concludes, then cvode:jacobian
/// from the sample it stopped at until the problem is no longer stiff there, then DOP853 again,
/// and so on (docs/theory.md §5.6, "Noticing stiffness during the run", "Returning to DOP853").
IntegratorStats integrate_switching(const OdeProblem& problem, const IntegratorOptions& options,
                                    const integration::OutputGrid& grid, std::vector<double>& y,
                                    const Observer& observer) {
  using integration::operator+;
  IntegratorOptions implicit = options;
  implicit.method = "cvode:jacobian";
  std::vector<std::string> switches;
  IntegratorStats stats;
  integration::OutputGrid rest = grid;
  bool stiff = false;  // the method of the piece now running: cvode:jacobian when true
  try {
    for (bool first = true;; first = false, stiff = !stiff) {
      // every piece after the first starts at a sample that is in the trajectory already
      bool seen = first;
      const Observer piece = [&](double t, double* yy, double* yp) {
        if (!seen) {
          seen = true;
          return ObserverAction::Continue;
        }
        return observer ? observer(t, yy, yp) : ObserverAction::Continue;
      };
      integration::Handover handover;
      stats = stats +
              (stiff ? integration::integrate_cvode(problem, implicit, rest, y, piece, &handover)
                     : integration::integrate_dop853(problem, options, rest, y, piece, &handover));
      if (!handover.handed) break;
      rest = rest.from(handover.sample);
      y = handover.y;
      switches.push_back(fmt::format(stiff ? "not stiff at t = {:.6g}: dop853 from t = {:.6g}"
                                           : "stiff at t = {:.6g}: cvode:jacobian from t = {:.6g}",
                                     handover.detected, rest.time(0)));
    }
  } catch (const IntegrationFailure& e) {
    IntegratorStats so_far = stats + e.stats();
    so_far.method = switch_summary(switches);
    throw IntegrationFailure(e, so_far);
  }
  stats.method = switch_summary(switches);
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
  const bool dae = method == "ida" || method == "ida:jacobian";
  if (dae || std::find(known.begin(), known.end(), method) == known.end()) {
    throw std::invalid_argument(
        fmt::format("integrator: unknown ODE method '{}', expected one of {}{}", method,
                    integrator_method_list(),
                    dae ? fmt::format(" ({} is for DAEs: use integrate_dae)", method) : ""));
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
  if (options.method != "ida" && options.method != "ida:jacobian") {
    throw std::invalid_argument(fmt::format(
        "integrator: unknown DAE method '{}', expected ida or ida:jacobian", options.method));
  }
  if (options.after_step)
    throw std::invalid_argument(
        fmt::format("integrator: {} takes no step hook (it restarts at samples)", options.method));
  if (options.method == "ida:jacobian" && !problem.jacobian.values)
    throw std::invalid_argument(
        "integrator: ida:jacobian needs the problem's exact Newton matrix (DaeProblem::jacobian)");
  integration::validate_options(options);
  validate_size(problem.size, y0.size(), "y0");
  validate_size(problem.size, yp0.size(), "yp0");
  validate_size(problem.size, problem.differential.size(), "differential");
  if (!problem.residual) throw std::invalid_argument("integrator: the DAE has no residual");
  const integration::OutputGrid grid(t0, t_end, dt);
  IntegratorStats stats = integration::integrate_ida(problem, options, grid, y0, yp0, observer);
  stats.method = options.method;
  return stats;
}

}  // namespace lagrange
