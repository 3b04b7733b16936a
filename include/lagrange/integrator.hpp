#pragma once
// Integrator front-end: DOP853 (explicit adaptive RK of order 8, the default), SUNDIALS ARKODE
// (explicit adaptive RK, named Butcher tables), CVODE (BDF), IDA (DAE), fixed-step RK4 and the
// fixed-step implicit midpoint rule, all reporting on a uniform output grid (DOP853, ARKODE and
// CVODE through their dense output, without stopping at samples).

#include <functional>
#include <string>
#include <vector>

namespace lagrange {

/// An exact Jacobian ∂f/∂y with a fixed sparsity pattern in compressed columns: the non-zeros
/// of column j are rows[column_starts[j] .. column_starts[j + 1]).
struct OdeJacobian {
  std::vector<long> column_starts;  ///< size + 1 entries, the first 0
  std::vector<long> rows;           ///< row of each non-zero, ascending within a column
  /// Writes ∂f/∂y at (t, y) in the pattern's order (rows.size() values).
  std::function<void(double t, const double* y, double* values)> values;
  size_t nonzeros() const { return rows.size(); }
};

/// An exact Newton matrix ∂F/∂y + c_j ∂F/∂y' of a DAE F(t, y, y') = 0 with a fixed sparsity
/// pattern in compressed columns (as OdeJacobian's).
struct DaeJacobian {
  std::vector<long> column_starts;  ///< size + 1 entries, the first 0
  std::vector<long> rows;           ///< row of each non-zero, ascending within a column
  /// Writes ∂F/∂y + cj ∂F/∂y' at (t, y, y') in the pattern's order (rows.size() values).
  std::function<void(double t, double cj, const double* y, const double* yp, double* values)>
      values;
  size_t nonzeros() const { return rows.size(); }
};

/// y' = f(t, y). `rhs` may throw lagrange::SimulationError; it is propagated unchanged.
struct OdeProblem {
  size_t size = 0;
  std::function<void(double t, const double* y, double* ydot)> rhs;
  /// Optional; required by `cvode:jacobian` (Newton matrices from it instead of difference
  /// quotients of rhs).
  OdeJacobian jacobian;
};

/// F(t, y, y') = 0 (IDA). `differential[i]` is true for components whose derivative appears.
struct DaeProblem {
  size_t size = 0;
  std::function<void(double t, const double* y, const double* yp, double* residual)> residual;
  std::vector<bool> differential;
  /// Optional; required by `ida:jacobian` (Newton matrices from it instead of difference
  /// quotients of the residual).
  DaeJacobian jacobian;
};

/// Called after every accepted internal step with the state y at t; may change y in place (e.g. a
/// projection onto constraints) and returns true when it did, so the method continues from there.
using StepHook = std::function<bool(double t, double* y)>;

/// The most intervals an output grid may have, (t_end − t0) / output step: 10⁸ samples, each a
/// row of the trajectory kept in memory (8 bytes per column); a finer grid is refused up front.
constexpr double kMaxOutputIntervals = 1e8;

/// How integrate() and integrate_dae() run: the method, its tolerances, step and limits.
struct IntegratorOptions {
  std::string method = "dop853";  ///< one of integrator_methods() (ODE); ida (DAE)
  double rtol = 1e-8;
  double atol = 1e-10;
  double step = 0.0;  ///< rk4 / midpoint step (0: output step / 10); dop853, arkode: > 0 fixes
                      ///< the step (no error control)
  long max_steps = 1000000;  ///< per output interval (adaptive methods; fixed steps at most)
  /// Highest BDF order of cvode, cvode:jacobian (also within auto), ida and ida:jacobian: 1 to 5
  /// (docs/theory.md §5.8).
  int max_order = 5;
  StepHook after_step;  ///< optional; ODE methods only (IDA restarts at samples instead)
};

/// An estimate of the spectral radius of ∂f/∂y at (t, y): the mean growth rate of 60 power
/// iterations (docs/theory.md §5.6, "Choosing the method").
double spectral_radius_estimate(const OdeJacobian& jacobian, double t,
                                const std::vector<double>& y);

/// ρ · output step above which `auto` treats a problem as stiff (docs/theory.md §5.6).
constexpr double kStiffnessThreshold = 100.0;

/// What `auto` runs: cvode:jacobian when ρ(∂f/∂y) at (t, y) times output_step exceeds
/// kStiffnessThreshold, else dop853 (also without a Jacobian).
std::string choose_ode_method(const OdeJacobian& jacobian, double t, const std::vector<double>& y,
                              double output_step);

/// Every method name integrate() and integrate_dae() accept, in the order help texts list them:
/// dop853 (the default), arkode (its default table), arkode:<table> for each named ARKODE explicit
/// table, cvode, cvode:jacobian (CVODE on the problem's exact sparse Jacobian), auto
/// (choose_ode_method at t0; starting on dop853 with a Jacobian at hand, it continues on
/// cvode:jacobian from the first sample after DOP853's stiffness test concludes, and on dop853
/// again once BDF's step h has h·ρ < 1; IntegratorStats::method says when), rk4, midpoint, ida,
/// ida:jacobian (IDA on the DAE's exact sparse Newton matrix, DaeProblem::jacobian).
const std::vector<std::string>& integrator_methods();

/// integrator_methods() joined by ", " (for messages that list the valid names).
std::string integrator_method_list();

/// What an integration did: steps taken and rejected, right-hand-side evaluations, the method.
struct IntegratorStats {
  long steps = 0;
  long rhs_evals = 0;
  long failed_steps = 0;
  /// what ran: plain `arkode` names its table, e.g. arkode:dormand-prince; `auto` that switched
  /// says where, e.g. "dop853, stiff at t = 0.0706: cvode:jacobian from t = 0.07, not stiff at
  /// t = 2.7: dop853 from t = 2.7"
  std::string method;
};

/// What the observer wants after seeing an output sample.
enum class ObserverAction { Continue, StateChanged, Stop };

/// Called at t0, t0 + dt, …, t_end with the state; it may modify y (return StateChanged so the
/// integrator restarts from it) or stop the run (Stop). For DAEs `yp` is the derivative, else null.
/// DOP853, ARKODE and CVODE step freely and hand the observer their dense-output interpolant at
/// each sample; changes to y there only take effect with StateChanged (the step past the sample is
/// discarded).
using Observer = std::function<ObserverAction(double t, double* y, double* yp)>;

/// Integrate an ODE on the uniform grid t0 + k·dt (last sample exactly t_end).
/// Throws SimulationError (with t) when the integrator fails, naming the SUNDIALS call and flag.
IntegratorStats integrate(const OdeProblem& problem, const IntegratorOptions& options, double t0,
                          std::vector<double> y0, double t_end, double dt,
                          const Observer& observer);

/// Integrate a DAE with IDA (`ida`, or `ida:jacobian` on problem.jacobian); y0/yp0 must be
/// consistent (or nearly: IDACalcIC corrects y' of the algebraic part). Same grid and observer
/// contract as `integrate`.
IntegratorStats integrate_dae(const DaeProblem& problem, const IntegratorOptions& options,
                              double t0, std::vector<double> y0, std::vector<double> yp0,
                              double t_end, double dt, const Observer& observer);

}  // namespace lagrange
