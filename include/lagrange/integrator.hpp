#pragma once
// Integrator front-end: SUNDIALS ARKODE (explicit adaptive RK), CVODE (BDF), IDA (DAE) and
// fixed-step RK4, all reporting on a uniform output grid.

#include <functional>
#include <string>
#include <vector>

namespace lagrange {

/// y' = f(t, y). `rhs` may throw lagrange::SimulationError; it is propagated unchanged.
struct OdeProblem {
  size_t size = 0;
  std::function<void(double t, const double* y, double* ydot)> rhs;
};

/// F(t, y, y') = 0 (IDA). `differential[i]` is true for components whose derivative appears.
struct DaeProblem {
  size_t size = 0;
  std::function<void(double t, const double* y, const double* yp, double* residual)> residual;
  std::vector<bool> differential;
};

struct IntegratorOptions {
  std::string method = "arkode";  ///< arkode | cvode | rk4 (ODE); ida (DAE)
  double rtol = 1e-8;
  double atol = 1e-10;
  double step = 0.0;         ///< rk4 step; 0 means output step / 10
  long max_steps = 1000000;  ///< per output interval (adaptive methods)
};

struct IntegratorStats {
  long steps = 0;
  long rhs_evals = 0;
  long failed_steps = 0;
};

/// What the observer wants after seeing an output sample.
enum class ObserverAction { Continue, StateChanged, Stop };

/// Called at t0, t0 + dt, …, t_end with the state; it may modify y (return StateChanged so the
/// integrator restarts from it) or stop the run (Stop). For DAEs `yp` is the derivative, else null.
using Observer = std::function<ObserverAction(double t, double* y, double* yp)>;

/// Integrate an ODE on the uniform grid t0 + k·dt (last sample exactly t_end).
/// Throws SimulationError (with t) when the integrator fails, naming the SUNDIALS call and flag.
IntegratorStats integrate(const OdeProblem& problem, const IntegratorOptions& options, double t0,
                          std::vector<double> y0, double t_end, double dt, const Observer& observer);

/// Integrate a DAE with IDA; y0/yp0 must be consistent (or nearly: IDACalcIC corrects y' of
/// the algebraic part). Same grid and observer contract as `integrate`.
IntegratorStats integrate_dae(const DaeProblem& problem, const IntegratorOptions& options, double t0,
                              std::vector<double> y0, std::vector<double> yp0, double t_end,
                              double dt, const Observer& observer);

}  // namespace lagrange
