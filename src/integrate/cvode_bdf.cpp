#include <cvode/cvode.h>
#include <cvode/cvode_ls.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "integrate/callbacks.hpp"
#include "integrate/keeping_stats.hpp"
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
  return {steps, evals + jac_evals, err_fails + solve_fails, {}};
}

}  // namespace

IntegratorStats integrate_cvode(const OdeProblem& problem, const IntegratorOptions& options,
                                const OutputGrid& grid, std::vector<double>& y,
                                const Observer& observer, Handover* handover) {
  const double t0 = grid.time(0);
  Context ctx;
  ErrorLog log;
  OdeCallback callback{problem, {}, {}};
  Vector y_vec = wrap_vector(y.data(), y.size(), ctx);
  // cvode:jacobian: Newton matrices from the exact Jacobian, sparse (KLU) when the build has it.
  const bool exact = options.method == "cvode:jacobian";
  const bool sparse = exact && have_klu();
  Matrix jacobian = sparse ? sparse_matrix(y.size(), problem.jacobian.nonzeros(), ctx)
                           : dense_matrix(y.size(), ctx);
  LinearSolver solver = sparse ? klu_solver(y_vec.get(), jacobian.get(), ctx)
                               : dense_solver(y_vec.get(), jacobian.get(), ctx);
  Memory<CVodeFree> mem(require_memory(CVodeCreate(CV_BDF, ctx.get()), "CVodeCreate"));
  const auto ok = [&](int flag, const char* call, double t) {
    check(flag, call, CVodeGetReturnFlagName, t, &log);
  };
  ok(CVodeSetErrHandlerFn(mem.get(), ErrorLog::handler, &log), "CVodeSetErrHandlerFn", t0);
  ok(CVodeInit(mem.get(), OdeCallback::rhs, t0, y_vec.get()), "CVodeInit", t0);
  ok(CVodeSetUserData(mem.get(), &callback), "CVodeSetUserData", t0);
  ok(CVodeSStolerances(mem.get(), options.rtol, options.atol), "CVodeSStolerances", t0);
  ok(CVodeSetMaxNumSteps(mem.get(), options.max_steps), "CVodeSetMaxNumSteps", t0);
  ok(CVodeSetMaxOrd(mem.get(), options.max_order), "CVodeSetMaxOrd", t0);
  check(CVodeSetLinearSolver(mem.get(), solver.get(), jacobian.get()), "CVodeSetLinearSolver",
        CVodeGetLinReturnFlagName, t0, &log);
  if (exact)
    check(CVodeSetJacFn(mem.get(), OdeCallback::jacobian), "CVodeSetJacFn",
          CVodeGetLinReturnFlagName, t0, &log);

  // Samples come from CVODE's Nordsieck interpolant (CVodeGetDky); only t_end is a stop.
  const double t_end = grid.time(grid.intervals());
  ok(CVodeSetStopTime(mem.get(), t_end), "CVodeSetStopTime", t0);
  std::vector<double> sample(y.size());
  Vector sample_vec = wrap_vector(sample.data(), sample.size(), ctx);

  IntegratorStats before_restart;
  StepBudget budget(options.max_steps);
  double t_reached = t0;
  long settling = 0;  // steps since the last (re)start
  const auto step = [&](double t_next) {
    budget.spend(t_next, t_reached, "CVode", "CV_TOO_MUCH_WORK");
    const int flag = CVode(mem.get(), t_end, y_vec.get(), &t_reached, CV_ONE_STEP);
    callback.guard.rethrow_pending();
    ok(flag, "CVode", t_reached);
    ++settling;
    return t_reached;
  };
  // docs/theory.md §5.6, "Returning to DOP853": with a handover, samples after the first compare
  // the settled step h with DOP853's stability bound from ρ(∂f/∂y) there; kReturnSamples in a
  // row far below it make that sample the last. A test that fails doubles the number of samples
  // until the next, up to kReturnSpacing (ρ costs a Jacobian and 60 products with it).
  size_t observed = 0, next_test = 1, spacing = 1;
  int soft = 0;
  const Observer watch = [&](double t, double* yy, double* yp) {
    const ObserverAction action = observer ? observer(t, yy, yp) : ObserverAction::Continue;
    const size_t k = observed++;
    if (action != ObserverAction::Continue || k < next_test || k == grid.intervals() ||
        settling < kSettledSteps)
      return action;
    double h = 0.0;
    ok(CVodeGetCurrentStep(mem.get(), &h), "CVodeGetCurrentStep", t);
    const std::vector<double> at(yy, yy + y.size());
    bool far_below = false;
    try {
      far_below = std::abs(h) * spectral_radius_estimate(problem.jacobian, t, at) < kReturnBound;
    } catch (const std::runtime_error&) {  // no Jacobian here (a singular KKT matrix): stay
    }
    soft = far_below ? soft + 1 : 0;
    spacing = far_below ? 1 : std::min<size_t>(2 * spacing, kReturnSpacing);
    next_test = k + spacing;
    if (soft < kReturnSamples) return action;
    *handover = {true, t, k, at};
    return ObserverAction::Stop;
  };
  const auto interpolate = [&](double t, double* out) {
    ok(CVodeGetDky(mem.get(), t, 0, sample_vec.get()), "CVodeGetDky", t);
    std::copy(sample.begin(), sample.end(), out);
  };
  const auto restart = [&](double t, bool /*keep_step*/) {  // BDF's history is gone either way
    before_restart = before_restart + cvode_stats(mem.get(), t, log);
    t_reached = t;
    settling = 0;
    ok(CVodeReInit(mem.get(), t, y_vec.get()), "CVodeReInit", t);
    ok(CVodeSetStopTime(mem.get(), t_end), "CVodeSetStopTime", t);
  };
  // BDF restarts at order 1 with a small step: drift is corrected once per output interval, after
  // the first step past each sample, not after every step.
  keeping_stats(
      [&] {
        walk_dense(grid, handover ? watch : observer, options.after_step, true, y, step,
                   interpolate, restart);
      },
      [&] { return before_restart + cvode_stats(mem.get(), t_reached, log); });
  return before_restart + cvode_stats(mem.get(), t_reached, log);
}

}  // namespace lagrange::integration
