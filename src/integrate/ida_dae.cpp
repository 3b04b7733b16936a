#include <ida/ida.h>
#include <ida/ida_ls.h>

#include <algorithm>

#include "integrate/callbacks.hpp"
#include "integrate/keeping_stats.hpp"
#include "integrate/methods.hpp"
#include "integrate/solver_errors.hpp"
#include "integrate/sundials_handles.hpp"
#include "integrate/walk_grid.hpp"

namespace lagrange::integration {

namespace {

/// Counters since the last (re)initialisation: residual evaluations include those of the
/// finite-difference Jacobian, failed steps count error-test and Newton failures.
IntegratorStats ida_stats(void* mem, double t, ErrorLog& log) {
  long steps = 0, evals = 0, jac_evals = 0, err_fails = 0, solve_fails = 0;
  const auto ok = [&](int flag, const char* call) {
    check(flag, call, IDAGetReturnFlagName, t, &log);
  };
  ok(IDAGetNumSteps(mem, &steps), "IDAGetNumSteps");
  ok(IDAGetNumResEvals(mem, &evals), "IDAGetNumResEvals");
  ok(IDAGetNumLinResEvals(mem, &jac_evals), "IDAGetNumLinResEvals");
  ok(IDAGetNumErrTestFails(mem, &err_fails), "IDAGetNumErrTestFails");
  ok(IDAGetNumStepSolveFails(mem, &solve_fails), "IDAGetNumStepSolveFails");
  return {steps, evals + jac_evals, err_fails + solve_fails, {}};
}

}  // namespace

IntegratorStats integrate_ida(const DaeProblem& problem, const IntegratorOptions& options,
                              const OutputGrid& grid, std::vector<double>& y,
                              std::vector<double>& yp, const Observer& observer) {
  const double t0 = grid.time(0);
  const size_t n = y.size();
  Context ctx;
  ErrorLog log;
  DaeCallback callback{problem, {}, {}};
  Vector y_vec = wrap_vector(y.data(), n, ctx);
  Vector yp_vec = wrap_vector(yp.data(), n, ctx);
  Vector id_vec = new_vector(n, ctx);
  double* id = N_VGetArrayPointer(id_vec.get());
  for (size_t i = 0; i < n; ++i) id[i] = problem.differential[i] ? 1.0 : 0.0;
  // ida:jacobian: Newton matrices from the exact sparse one, in KLU when the build has it.
  const bool exact = options.method == "ida:jacobian";
  const bool sparse = exact && have_klu();
  Matrix jacobian =
      sparse ? sparse_matrix(n, problem.jacobian.nonzeros(), ctx) : dense_matrix(n, ctx);
  LinearSolver solver = sparse ? klu_solver(y_vec.get(), jacobian.get(), ctx)
                               : dense_solver(y_vec.get(), jacobian.get(), ctx);
  Memory<IDAFree> mem(require_memory(IDACreate(ctx.get()), "IDACreate"));
  const auto ok = [&](int flag, const char* call, double t) {
    check(flag, call, IDAGetReturnFlagName, t, &log);
  };
  ok(IDASetErrHandlerFn(mem.get(), ErrorLog::handler, &log), "IDASetErrHandlerFn", t0);
  ok(IDAInit(mem.get(), DaeCallback::residual, t0, y_vec.get(), yp_vec.get()), "IDAInit", t0);
  ok(IDASetUserData(mem.get(), &callback), "IDASetUserData", t0);
  ok(IDASStolerances(mem.get(), options.rtol, options.atol), "IDASStolerances", t0);
  ok(IDASetMaxNumSteps(mem.get(), options.max_steps), "IDASetMaxNumSteps", t0);
  ok(IDASetMaxOrd(mem.get(), options.max_order), "IDASetMaxOrd", t0);
  ok(IDASetId(mem.get(), id_vec.get()), "IDASetId", t0);
  // docs/theory.md §5.6, "The DAE's Newton matrix": the algebraic components (the multipliers λ)
  // follow from the differential ones and stay out of the local error test.
  if (std::find(problem.differential.begin(), problem.differential.end(), false) !=
      problem.differential.end())
    ok(IDASetSuppressAlg(mem.get(), SUNTRUE), "IDASetSuppressAlg", t0);
  check(IDASetLinearSolver(mem.get(), solver.get(), jacobian.get()), "IDASetLinearSolver",
        IDAGetLinReturnFlagName, t0, &log);
  if (exact)
    check(IDASetJacFn(mem.get(), DaeCallback::jacobian), "IDASetJacFn", IDAGetLinReturnFlagName, t0,
          &log);

  // Make (y, y') consistent at t: given the differential y, solve F = 0 for the algebraic y and
  // for y' (IDA_YA_YDP_INIT), then copy the corrected values back into y and yp.
  const auto consistent_start = [&](double t, double t_first_output) {
    const int flag = IDACalcIC(mem.get(), IDA_YA_YDP_INIT, t_first_output);
    callback.guard.rethrow_pending();
    ok(flag, "IDACalcIC", t);
    ok(IDAGetConsistentIC(mem.get(), y_vec.get(), yp_vec.get()), "IDAGetConsistentIC", t);
  };
  // IDACalcIC only uses its tout1 argument for direction and scale: the next sample will do, but
  // no further than 1 s ahead (a sample a simulated day away made its line search fail on the
  // double pendulum's exact start).
  const double t_end = grid.time(grid.intervals());
  const auto next_time = [&](double t) {
    const double step = std::min(grid.step(), 1.0);
    return t < t_end ? std::min(t + step, t_end) : t + step;
  };
  consistent_start(t0, next_time(t0));

  // Samples come from IDA's interpolant (IDA_NORMAL steps past each one); only t_end is a stop,
  // so a sample neither cuts a step nor, unless the observer changes the state, restarts IDA.
  ok(IDASetStopTime(mem.get(), t_end), "IDASetStopTime", t0);
  IntegratorStats before_restart;
  double t_reached = t0;
  const auto advance = [&](double t_next) {
    const int flag = IDASolve(mem.get(), t_next, &t_reached, y_vec.get(), yp_vec.get(), IDA_NORMAL);
    callback.guard.rethrow_pending();
    ok(flag, "IDASolve", t_reached);
  };
  const auto restart = [&](double t) {
    before_restart = before_restart + ida_stats(mem.get(), t, log);
    ok(IDAReInit(mem.get(), t, y_vec.get(), yp_vec.get()), "IDAReInit", t);
    ok(IDASetStopTime(mem.get(), t_end), "IDASetStopTime", t);
    consistent_start(t, next_time(t));
  };
  keeping_stats([&] { walk_grid(grid, observer, y.data(), yp.data(), advance, restart); },
                [&] { return before_restart + ida_stats(mem.get(), t_reached, log); });
  return before_restart + ida_stats(mem.get(), t_reached, log);
}

}  // namespace lagrange::integration
