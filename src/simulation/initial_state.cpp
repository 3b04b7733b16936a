#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lagrange/simulation.hpp"
#include "simulation/max_abs.hpp"

namespace lagrange {

namespace {

/// Gauss–Newton to well below `tol`, so that the state is consistent with a margin.
constexpr double kProjectionTarget = 1e-13;

}  // namespace

std::string InitialConsistency::note() const {
  return fmt::format(
      "initial state was inconsistent (max |C| = {:.3g}, max |Ċ| = {:.3g}); projected onto the "
      "constraints (|Δq| = {:.3g}, |Δv| = {:.3g}):{}",
      max_abs(C0), max_abs(Cdot0), projection.position_change, projection.velocity_change, changes);
}

// docs/theory.md §4.3: a consistent start is the least-squares change of the coordinates not
// marked fixed that gives C = 0, then of their velocities that gives Ċ = 0.
InitialConsistency make_initial_state_consistent(Dynamics& dyn, double t0, std::vector<double>& q,
                                                 std::vector<double>& v, double tol) {
  const CompiledModel& cm = dyn.model();
  InitialConsistency ic;
  if (cm.m == 0) return ic;
  ic.C0.resize(cm.m);
  ic.Cdot0.resize(cm.m);
  dyn.constraints(t0, q.data(), v.data(), ic.C0.data(), ic.Cdot0.data());
  ic.C = ic.C0;
  ic.Cdot = ic.Cdot0;
  auto within = [tol](const std::vector<double>& C, const std::vector<double>& Cdot) {
    return max_abs(C) <= tol && max_abs(Cdot) <= tol;
  };
  if (within(ic.C0, ic.Cdot0)) return ic;
  ic.was_consistent = false;
  const std::vector<double> q_old = q, v_old = v;
  ic.projection = dyn.try_project(t0, q.data(), v.data(), cm.fixed, kProjectionTarget);
  dyn.constraints(t0, q.data(), v.data(), ic.C.data(), ic.Cdot.data());
  // Consistent to the tolerance, or to the rounding floors of C and Ċ where those are larger
  // (distance constraints over 200 m: |C| ~ 1e-11 is as exact as floating point allows).
  ic.consistent =
      within(ic.C, ic.Cdot) || (max_abs(ic.C) <= std::max(tol, ic.projection.floor) &&
                                max_abs(ic.Cdot) <= std::max(tol, ic.projection.rate_floor));
  // Each change that shows at ten digits; those that do not are counted, not listed as "x -> x".
  size_t unseen = 0;
  const auto list = [&](const std::string& name, double before, double after) {
    if (before == after) return;
    const std::string a = fmt::format("{:.10g}", before), b = fmt::format("{:.10g}", after);
    if (a == b)
      ++unseen;
    else
      ic.changes += fmt::format("\n  {}: {} -> {}", name, a, b);
  };
  for (size_t i = 0; i < cm.nq; ++i) list(cm.coordinate_names[i], q_old[i], q[i]);
  for (size_t i = 0; i < cm.nv; ++i) list(cm.velocity_names[i], v_old[i], v[i]);
  if (unseen > 0)
    ic.changes += fmt::format("\n  ({} {} changed below the tenth digit)", unseen,
                              unseen == 1 ? "value" : "values");
  if (!ic.consistent && std::find(cm.fixed.begin(), cm.fixed.end(), true) != cm.fixed.end()) {
    std::vector<double> q_free = q_old, v_free = v_old, C(cm.m), Cdot(cm.m);
    dyn.try_project(t0, q_free.data(), v_free.data(), {}, kProjectionTarget);
    dyn.constraints(t0, q_free.data(), v_free.data(), C.data(), Cdot.data());
    ic.blocked_by_fixed = within(C, Cdot);
  }
  return ic;
}

}  // namespace lagrange
