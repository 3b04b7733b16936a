#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>

#include "integrate/callbacks.hpp"
#include "integrate/methods.hpp"
#include "integrate/solver_errors.hpp"
#include "integrate/sundials_handles.hpp"
#include "integrate/walk_grid.hpp"

namespace lagrange::integration {

namespace {

/// Counters since the last (re)initialisation: rhs evaluations include those of the
/// finite-difference Jacobian, failed steps count error-test and Newton failures.
IntegratorStats cvode_stats(void* mem, double t, ErrorLog& log) {
  long steps = 0, evals = 0, jac_evals = 0, err_fails = 0, solve_fails = 0;
  const auto ok = [&](int flag, const char* call) {
    check(flag, call, CVodeGetReturnFlagName, t, &log);
  };
  ok(CVodeGetNumSteps(mem, &steps), "CVodeGetNumSteps");
  ok(CVodeGetNumRhsEvals(mem, &evals), "CVodeGetNumRhsEvals");
  ok(CVodeGetNumLinRhsEvals(mem, &jac_evals), "CVodeGetNumLinRhsEvals");
  ok(CVodeGetNumErrTestFails(mem, &err_fails), "CVodeGetNumErrTestFails");
  ok(CVodeGetNumStepSolveFails(mem, &solve_fails), "CVodeGetNumStepSolveFails");
  return {steps, evals + jac_evals, err_fails + solve_fails};
}

}  // namespace

IntegratorStats integrate_cvode(const OdeProblem& problem, const IntegratorOptions& options,
                                const OutputGrid& grid, std::vector<double>& y,
                                const Observer& observer) {
  const double t0 = grid.time(0);
  Context ctx;
  ErrorLog log;
  OdeCallback callback{problem, {}};
  Vector y_vec = wrap_vector(y.data(), y.size(), ctx);
  Matrix jacobian = dense_matrix(y.size(), ctx);
  LinearSolver solver = dense_solver(y_vec.get(), jacobian.get(), ctx);
  Memory<CVodeFree> mem(require_memory(CVodeCreate(CV_BDF, ctx.get()), "CVodeCreate"));
  const auto ok = [&](int flag, const char* call, double t) {
    check(flag, call, CVodeGetReturnFlagName, t, &log);
  };
  ok(CVodeSetErrHandlerFn(mem.get(), ErrorLog::handler, &log), "CVodeSetErrHandlerFn", t0);
  ok(CVodeInit(mem.get(), OdeCallback::rhs, t0, y_vec.get()), "CVodeInit", t0);
  ok(CVodeSetUserData(mem.get(), &callback), "CVodeSetUserData", t0);
  ok(CVodeSStolerances(mem.get(), options.rtol, options.atol), "CVodeSStolerances", t0);
  ok(CVodeSetMaxNumSteps(mem.get(), options.max_steps), "CVodeSetMaxNumSteps", t0);
  check(CVodeSetLinearSolver(mem.get(), solver.get(), jacobian.get()), "CVodeSetLinearSolver",
        CVodeGetLinReturnFlagName, t0, &log);

  IntegratorStats before_restart;
  double t_reached = t0;
  const auto advance = [&](double t_next) {
    // Stop time = next sample: CVODE lands on it exactly instead of interpolating past it.
    ok(CVodeSetStopTime(mem.get(), t_next), "CVodeSetStopTime", t_reached);
    const int flag = CVode(mem.get(), t_next, y_vec.get(), &t_reached, CV_NORMAL);
    callback.guard.rethrow_pending();
    ok(flag, "CVode", t_reached);
  };
  const auto restart = [&](double t) {
    before_restart = before_restart + cvode_stats(mem.get(), t, log);
    ok(CVodeReInit(mem.get(), t, y_vec.get()), "CVodeReInit", t);
  };
  walk_grid(grid, observer, y.data(), nullptr, advance, restart);
  return before_restart + cvode_stats(mem.get(), t_reached, log);
}

}  // namespace lagrange::integration
