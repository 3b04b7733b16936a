#include "simulation/start_state.hpp"

#include <fmt/format.h>

#include "lagrange/error.hpp"
#include "simulation/max_abs.hpp"

namespace lagrange {

// docs/theory.md §4.3: check C = 0 and Ċ = 0, project if needed and say what moved.
void make_consistent(Dynamics& dyn, const SimulationOptions& opt, std::vector<double>& q,
                     std::vector<double>& v, Trajectory& traj) {
  const CompiledModel& cm = dyn.model();
  if (cm.m == 0) return;
  if (!opt.project_initial) {
    std::vector<double> C(cm.m), Cdot(cm.m);
    dyn.constraints(opt.t0, q.data(), v.data(), C.data(), Cdot.data());
    const double err = max_abs(C), rate_err = max_abs(Cdot);
    if (err <= opt.projection_tol && rate_err <= opt.projection_tol) return;
    throw SimulationError(opt.t0,
                          fmt::format("the initial state is inconsistent: max |C| = {:.3g}, "
                                      "max |Ċ| = {:.3g}",
                                      err, rate_err));
  }
  const InitialConsistency ic =
      make_initial_state_consistent(dyn, opt.t0, q, v, opt.projection_tol);
  if (!ic.consistent)
    throw SimulationError(
        opt.t0,
        fmt::format("the initial state cannot be made consistent: after projection max "
                    "|C| = {:.3g}, max |Ċ| = {:.3g} (at the start {:.3g} and {:.3g}){}",
                    max_abs(ic.C), max_abs(ic.Cdot), max_abs(ic.C0), max_abs(ic.Cdot0),
                    ic.blocked_by_fixed ? "; the coordinates marked fixed stand in the way" : ""));
  if (!ic.was_consistent) traj.notes.push_back(ic.note());
}

}  // namespace lagrange
