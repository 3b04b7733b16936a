#pragma once
// C callbacks handed to SUNDIALS. user_data points at one of these structs; exceptions (including
// the SimulationError raised for a NaN/Inf result) are caught by `guard` and rethrown by the
// driver.

#include <sundials/sundials_matrix.h>
#include <sundials/sundials_nvector.h>

#include <vector>

#include "integrate/callback_guard.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange::integration {

/// y' = f(t, y) for ARKODE and CVODE.
struct OdeCallback {
  const OdeProblem& problem;
  CallbackGuard guard;
  /// ARKRhsFn / CVRhsFn: ydot = f(t, y); returns -1 after storing an exception.
  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* self);
  /// CVLsJacFn: J = ∂f/∂y from problem.jacobian into a sparse (compressed-column) or dense
  /// SUNMatrix; returns -1 after storing an exception.
  static int jacobian(sunrealtype t, N_Vector y, N_Vector fy, SUNMatrix J, void* self,
                      N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);
  std::vector<double> values;  ///< scratch for problem.jacobian's non-zeros
};

/// F(t, y, y') for IDA.
struct DaeCallback {
  const DaeProblem& problem;
  CallbackGuard guard;
  /// IDAResFn: r = F(t, y, y'); returns -1 after storing an exception.
  static int residual(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, void* self);
  /// IDALsJacFn: J = ∂F/∂y + c_j ∂F/∂y' from problem.jacobian into a sparse (compressed-column)
  /// or dense SUNMatrix; returns -1 after storing an exception.
  static int jacobian(sunrealtype t, sunrealtype cj, N_Vector y, N_Vector yp, N_Vector r,
                      SUNMatrix J, void* self, N_Vector tmp1, N_Vector tmp2, N_Vector tmp3);
  std::vector<double> values;  ///< scratch for problem.jacobian's non-zeros
};

}  // namespace lagrange::integration
