#include <arkode/arkode_erkstep.h>

#include "integrate/callbacks.hpp"
#include "integrate/methods.hpp"
#include "integrate/solver_errors.hpp"
#include "integrate/sundials_handles.hpp"
#include "integrate/walk_grid.hpp"

namespace lagrange::integration {

namespace {

/// Counters since the last (re)initialisation of an ERKStep memory.
IntegratorStats erk_stats(void* mem, double t, ErrorLog& log) {
  long steps = 0, evals = 0, failed = 0;
  check(ERKStepGetNumSteps(mem, &steps), "ERKStepGetNumSteps", ERKStepGetReturnFlagName, t, &log);
  check(ERKStepGetNumRhsEvals(mem, &evals), "ERKStepGetNumRhsEvals", ERKStepGetReturnFlagName, t,
        &log);
  check(ERKStepGetNumErrTestFails(mem, &failed), "ERKStepGetNumErrTestFails",
        ERKStepGetReturnFlagName, t, &log);
  return {steps, evals, failed};
}

}  // namespace

IntegratorStats integrate_arkode(const OdeProblem& problem, const IntegratorOptions& options,
                                 const OutputGrid& grid, std::vector<double>& y,
                                 const Observer& observer) {
  const double t0 = grid.time(0);
  Context ctx;
  ErrorLog log;
  OdeCallback callback{problem, {}};
  Vector y_vec = wrap_vector(y.data(), y.size(), ctx);
  Memory<ERKStepFree> mem(
      require_memory(ERKStepCreate(OdeCallback::rhs, t0, y_vec.get(), ctx.get()), "ERKStepCreate"));
  const auto ok = [&](int flag, const char* call, double t) {
    check(flag, call, ERKStepGetReturnFlagName, t, &log);
  };
  ok(ERKStepSetErrHandlerFn(mem.get(), ErrorLog::handler, &log), "ERKStepSetErrHandlerFn", t0);
  ok(ERKStepSetUserData(mem.get(), &callback), "ERKStepSetUserData", t0);
  ok(ERKStepSStolerances(mem.get(), options.rtol, options.atol), "ERKStepSStolerances", t0);
  ok(ERKStepSetMaxNumSteps(mem.get(), options.max_steps), "ERKStepSetMaxNumSteps", t0);

  IntegratorStats before_restart;
  double t_reached = t0;
  const auto advance = [&](double t_next) {
    // Stop time = next sample: ARKODE lands on it exactly instead of interpolating past it.
    ok(ERKStepSetStopTime(mem.get(), t_next), "ERKStepSetStopTime", t_reached);
    const int flag = ERKStepEvolve(mem.get(), t_next, y_vec.get(), &t_reached, ARK_NORMAL);
    callback.guard.rethrow_pending();
    ok(flag, "ERKStepEvolve", t_reached);
  };
  const auto restart = [&](double t) {
    before_restart = before_restart + erk_stats(mem.get(), t, log);
    ok(ERKStepReInit(mem.get(), OdeCallback::rhs, t, y_vec.get()), "ERKStepReInit", t);
  };
  walk_grid(grid, observer, y.data(), nullptr, advance, restart);
  return before_restart + erk_stats(mem.get(), t_reached, log);
}

}  // namespace lagrange::integration
