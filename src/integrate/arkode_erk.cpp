#include <arkode/arkode_erkstep.h>

#include <memory>
#include <stdexcept>
#include <vector>

#include "integrate/callbacks.hpp"
#include "integrate/erk_tables.hpp"
#include "integrate/hermite_dense.hpp"
#include "integrate/keeping_stats.hpp"
#include "integrate/methods.hpp"
#include "integrate/solver_errors.hpp"
#include "integrate/sundials_handles.hpp"
#include "integrate/walk_grid.hpp"

namespace lagrange::integration {

namespace {

/// Counters since the last ERKStepReInit (ERKStepReset keeps them).
IntegratorStats erk_stats(void* mem, double t, ErrorLog& log) {
  long steps = 0, evals = 0, failed = 0;
  check(ERKStepGetNumSteps(mem, &steps), "ERKStepGetNumSteps", ERKStepGetReturnFlagName, t, &log);
  check(ERKStepGetNumRhsEvals(mem, &evals), "ERKStepGetNumRhsEvals", ERKStepGetReturnFlagName, t,
        &log);
  check(ERKStepGetNumErrTestFails(mem, &failed), "ERKStepGetNumErrTestFails",
        ERKStepGetReturnFlagName, t, &log);
  return {steps, evals, failed, {}};
}

using Table = std::unique_ptr<ARKodeButcherTableMem, void (*)(ARKodeButcherTable)>;

/// ARKODE's table `table.id`, or one built from the published coefficients `table.own()`.
Table load_table(const ErkTable& table) {
  if (table.own == nullptr) {
    Table loaded(ARKodeButcherTable_LoadERK(static_cast<ARKODE_ERKTableID>(table.id)),
                 ARKodeButcherTable_Free);
    if (!loaded) throw std::runtime_error("SUNDIALS: ARKodeButcherTable_LoadERK failed");
    return loaded;
  }
  const ButcherCoefficients& k = table.own();
  const int s = static_cast<int>(k.c.size());
  std::vector<double> c = k.c, b = k.b, d = k.d, a(k.c.size() * k.c.size(), 0.0);
  for (int i = 0; i < s; ++i)
    for (int j = 0; j < i; ++j) a[i * s + j] = k.a[i][j];  // row-major s × s
  Table created(
      ARKodeButcherTable_Create(s, k.order, k.embedding, c.data(), a.data(), b.data(), d.data()),
      ARKodeButcherTable_Free);
  if (!created) throw std::runtime_error("SUNDIALS: ARKodeButcherTable_Create failed");
  return created;
}

/// Hands ARKODE the table. SUNDIALS 6.4's ERKStep reuses the last stage's f as the next
/// step's first (first same as last) whenever the last node c is 1, which is right only when the
/// last row of A equals b (Dormand–Prince, Bogacki–Shampine); for Verner 6(5) it lowers the order
/// to 3 and for Sayfy–Aburub to 2, and the dense output takes a wrong f at the step's end
/// (tests/integrate/test_erk_tables.cpp). Those tables get one more stage, row b and node 1, with
/// weight 0 in both solutions: it evaluates f(t + h, y₁), which the reuse then makes correct, so a
/// step still costs `stages` evaluations.
void set_table(void* mem, const ErkTable& erk, double t0, ErrorLog& log) {
  Table table = load_table(erk);
  const int s = table->stages;
  bool first_same_as_last = true;
  for (int j = 0; j < s; ++j)
    first_same_as_last = first_same_as_last && table->A[s - 1][j] == table->b[j];
  if (table->c[s - 1] == 1.0 && !first_same_as_last) {
    Table closed(ARKodeButcherTable_Alloc(s + 1, SUNTRUE), ARKodeButcherTable_Free);
    if (!closed) throw std::runtime_error("SUNDIALS: ARKodeButcherTable_Alloc failed");
    closed->q = table->q;
    closed->p = table->p;
    for (int i = 0; i < s; ++i) {
      closed->c[i] = table->c[i];
      closed->b[i] = table->b[i];
      closed->d[i] = table->d[i];
      for (int j = 0; j < i; ++j) closed->A[i][j] = table->A[i][j];
      closed->A[s][i] = table->b[i];
    }
    closed->c[s] = 1.0;
    closed->b[s] = closed->d[s] = 0.0;
    table = std::move(closed);
  }
  check(ERKStepSetTable(mem, table.get()), "ERKStepSetTable", ERKStepGetReturnFlagName, t0, &log);
}

/// The table `method` names: `arkode` (the default for rtol) or `arkode:<table>`.
const ErkTable& table_for(const IntegratorOptions& options) {
  const std::string prefix = "arkode:";
  if (options.method.compare(0, prefix.size(), prefix) != 0) return default_erk_table(options.rtol);
  const ErkTable* table = find_erk_table(options.method.substr(prefix.size()));
  if (table == nullptr) throw std::invalid_argument("integrator: unknown ARKODE table");
  return *table;
}

}  // namespace

IntegratorStats integrate_arkode(const OdeProblem& problem, const IntegratorOptions& options,
                                 const OutputGrid& grid, std::vector<double>& y,
                                 const Observer& observer) {
  const double t0 = grid.time(0);
  const double t_end = grid.time(grid.intervals());
  Context ctx;
  ErrorLog log;
  OdeCallback callback{problem, {}, {}};
  Vector y_vec = wrap_vector(y.data(), y.size(), ctx);
  std::vector<double> sample(y.size());
  Vector sample_vec = wrap_vector(sample.data(), sample.size(), ctx);
  Memory<ERKStepFree> mem(
      require_memory(ERKStepCreate(OdeCallback::rhs, t0, y_vec.get(), ctx.get()), "ERKStepCreate"));
  const auto ok = [&](int flag, const char* call, double t) {
    check(flag, call, ERKStepGetReturnFlagName, t, &log);
  };
  ok(ERKStepSetErrHandlerFn(mem.get(), ErrorLog::handler, &log), "ERKStepSetErrHandlerFn", t0);
  ok(ERKStepSetUserData(mem.get(), &callback), "ERKStepSetUserData", t0);
  const ErkTable& table = table_for(options);
  set_table(mem.get(), table, t0, log);
  ok(ERKStepSStolerances(mem.get(), options.rtol, options.atol), "ERKStepSStolerances", t0);
  if (options.step > 0.0)  // fixed step, no error control (order studies, fixed-cost runs)
    ok(ERKStepSetFixedStep(mem.get(), options.step), "ERKStepSetFixedStep", t0);
  // ARKODE's cubic Hermite interpolant gives y and f exactly at the ends of the last step; the
  // samples come from the Hermite polynomial through the last step ends (hermite_dense.hpp).
  ok(ERKStepSetInterpolantType(mem.get(), ARK_INTERP_HERMITE), "ERKStepSetInterpolantType", t0);
  ok(ERKStepSetInterpolantDegree(mem.get(), 3), "ERKStepSetInterpolantDegree", t0);
  // Samples come from the interpolant, so the steps need not stop at them; only t_end is a stop.
  ok(ERKStepSetStopTime(mem.get(), t_end), "ERKStepSetStopTime", t0);

  IntegratorStats before_restart;
  StepBudget budget(options.max_steps);
  HermiteDense dense(y.size(), table.order > 6 ? 6 : 4);
  double t_reached = t0;
  const auto node = [&](double t, int derivative) {
    ok(ERKStepGetDky(mem.get(), t, derivative, sample_vec.get()), "ERKStepGetDky", t);
    return sample.data();
  };
  std::vector<double> y_start(y.size());
  const auto step = [&](double t_next) {
    budget.spend(t_next, t_reached, "ERKStepEvolve", "ARK_TOO_MUCH_WORK");
    const double t_start = t_reached;
    const int flag = ERKStepEvolve(mem.get(), t_end, y_vec.get(), &t_reached, ARK_ONE_STEP);
    callback.guard.rethrow_pending();
    ok(flag, "ERKStepEvolve", t_reached);
    if (dense.newest() != t_start) {  // the first step since a (re)start: its start is a node
      dense.clear();
      y_start.assign(sample.size(), 0.0);
      const double* start = node(t_start, 0);
      std::copy(start, start + sample.size(), y_start.begin());
      dense.push(t_start, y_start.data(), node(t_start, 1));
    }
    dense.push(t_reached, y.data(), node(t_reached, 1));
    return t_reached;
  };
  const auto interpolate = [&](double t, double* out) { dense.evaluate(t, out); };
  // A correction after a step: ERKStepReset keeps the step size and the counters. A new state
  // from the observer: ERKStepReInit, as a fresh run from there would start.
  const auto restart = [&](double t, bool keep_step) {
    t_reached = t;
    if (keep_step) {
      ok(ERKStepReset(mem.get(), t, y_vec.get()), "ERKStepReset", t);
    } else {
      before_restart = before_restart + erk_stats(mem.get(), t, log);
      ok(ERKStepReInit(mem.get(), OdeCallback::rhs, t, y_vec.get()), "ERKStepReInit", t);
    }
    ok(ERKStepSetStopTime(mem.get(), t_end), "ERKStepSetStopTime", t);  // both forget it
  };
  keeping_stats(
      [&] { walk_dense(grid, observer, options.after_step, false, y, step, interpolate, restart); },
      [&] { return before_restart + erk_stats(mem.get(), t_reached, log); });
  return before_restart + erk_stats(mem.get(), t_reached, log);
}

}  // namespace lagrange::integration
