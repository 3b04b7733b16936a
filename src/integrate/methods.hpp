#pragma once
// One function per integration method; inputs are validated by the front-end (integrator.cpp).
// Each integrates `y` (and `yp`) in place along `grid`, calling `observer` at every sample.

#include <vector>

#include "integrate/output_grid.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange::integration {

/// Throws std::invalid_argument unless the tolerances, step and step limit make sense.
void validate_options(const IntegratorOptions& options);

/// ARKODE ERKStep, explicit adaptive Runge–Kutta with the table options.method names (`arkode`:
/// the default for the tolerance, erk_tables.hpp); samples from ARKODE's interpolant.
IntegratorStats integrate_arkode(const OdeProblem& problem, const IntegratorOptions& options,
                                 const OutputGrid& grid, std::vector<double>& y,
                                 const Observer& observer);

/// Where a run under `auto` stopped to hand over to the other method: DOP853 when its stiffness
/// test concluded (Dop853::stiff), cvode:jacobian when the problem was no longer stiff.
struct Handover {
  bool handed = false;
  double detected = 0.0;  ///< the time the test concluded
  size_t sample = 0;      ///< the grid sample the run stopped at (observed already)
  std::vector<double> y;  ///< the state there, as the observer saw it
};

/// cvode:jacobian under `auto` hands back to DOP853 when its step h, settled (kSettledSteps
/// steps after a (re)start), satisfies h·ρ(∂f/∂y) < kReturnBound at kReturnSamples tested
/// samples in a row: the explicit method's stability bound (h·ρ ≈ 6.1) is then far above the
/// step accuracy asks for; after a failed test the next comes up to kReturnSpacing samples later
/// (docs/theory.md §5.6, "Returning to DOP853").
constexpr double kReturnBound = 1.0;
constexpr long kSettledSteps = 10;
constexpr int kReturnSamples = 3;
constexpr size_t kReturnSpacing = 32;

/// DOP853 (Dormand–Prince 8(5,3), Hairer's error estimate and step control), samples from its
/// continuous extension of order 7; options.step > 0 fixes the step (no error control). With
/// `handover`, the run ends at the first sample after the stiffness test concludes, and says
/// where in it (docs/theory.md §5.6, "Noticing stiffness during the run").
IntegratorStats integrate_dop853(const OdeProblem& problem, const IntegratorOptions& options,
                                 const OutputGrid& grid, std::vector<double>& y,
                                 const Observer& observer, Handover* handover = nullptr);

/// CVODE BDF (orders 1–5) with Newton iteration; `cvode`: a dense direct linear solver on
/// difference-quotient Jacobians, `cvode:jacobian`: problem.jacobian, in KLU when the build has
/// it (else dense); samples from CVODE's interpolant. With `handover` (cvode:jacobian only), the
/// run ends at the first sample where the problem is no longer stiff (kReturnBound), and says
/// where.
IntegratorStats integrate_cvode(const OdeProblem& problem, const IntegratorOptions& options,
                                const OutputGrid& grid, std::vector<double>& y,
                                const Observer& observer, Handover* handover = nullptr);

/// Classical fixed-step RK4, an integer number of equal steps per output interval.
IntegratorStats integrate_rk4(const OdeProblem& problem, const IntegratorOptions& options,
                              const OutputGrid& grid, std::vector<double>& y,
                              const Observer& observer);

/// The implicit midpoint rule y₁ = y₀ + h f(t + h/2, (y₀ + y₁)/2), fixed step, an integer number
/// of equal steps per output interval; solved by fixed-point iteration to rounding level.
IntegratorStats integrate_midpoint(const OdeProblem& problem, const IntegratorOptions& options,
                                   const OutputGrid& grid, std::vector<double>& y,
                                   const Observer& observer);

/// IDA (variable-order BDF for F(t, y, y') = 0) with IDACalcIC: `ida` on dense difference-quotient
/// Newton matrices, `ida:jacobian` on problem.jacobian, in KLU when the build has it (else dense).
IntegratorStats integrate_ida(const DaeProblem& problem, const IntegratorOptions& options,
                              const OutputGrid& grid, std::vector<double>& y,
                              std::vector<double>& yp, const Observer& observer);

}  // namespace lagrange::integration
