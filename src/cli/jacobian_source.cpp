// The exact Jacobian every front-end hands its runs (src/cli/prepare.hpp, jacobian_source).

#include <fmt/format.h>

#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "lagrange/analysis.hpp"

namespace lagrange::cli {

// docs/theory.md §5.6, "One Jacobian for every entry point".
JacobianSource jacobian_source(const Prepared& p, const std::string& method,
                               const std::string& lagrangian_hint) {
  if (!uses_jacobian(method)) return {};
  if (p.equations.recursive) {
    if (method == "auto") return {};
    throw UsageError(fmt::format(
        "integrator {} needs the Lagrangian formulation (the recursive one has no exact "
        "Jacobian): {}",
        method, lagrangian_hint));
  }
  if (!p.jacobian) {
    try {
      p.jacobian = std::make_shared<const DynamicsJacobian>(p.equations, p.compiled);
    } catch (const std::invalid_argument& e) {
      if (method != "auto") throw UsageError(fmt::format("integrator {}: {}", method, e.what()));
      return {};
    }
  }
  // The Jacobian each run builds keeps the tape alive for as long as the run holds it.
  JacobianSource source;
  source.ode = [jac = p.jacobian](Dynamics& dynamics, double t0, const std::vector<double>& y0) {
    OdeJacobian out = ode_jacobian(*jac, dynamics, t0, y0);
    out.values = [jac, values = std::move(out.values)](double t, const double* y, double* v) {
      values(t, y, v);
    };
    return out;
  };
  source.dae = [jac = p.jacobian](Dynamics& dynamics, double t0, const std::vector<double>& y0) {
    DaeJacobian out = dae_jacobian(*jac, dynamics, t0, y0);
    out.values = [jac, values = std::move(out.values)](double t, double cj, const double* y,
                                                       const double* yp,
                                                       double* v) { values(t, cj, y, yp, v); };
    return out;
  };
  return source;
}

}  // namespace lagrange::cli
