#include "integrate/callbacks.hpp"

#include "integrate/solver_errors.hpp"

namespace lagrange::integration {

int OdeCallback::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* self) {
  auto* cb = static_cast<OdeCallback*>(self);
  return cb->guard.run([&] {
    double* out = N_VGetArrayPointer(ydot);
    cb->problem.rhs(t, N_VGetArrayPointer(y), out);
    ensure_finite(t, out, cb->problem.size, "right-hand side ydot");
  });
}

int DaeCallback::residual(sunrealtype t, N_Vector y, N_Vector yp, N_Vector r, void* self) {
  auto* cb = static_cast<DaeCallback*>(self);
  return cb->guard.run([&] {
    double* out = N_VGetArrayPointer(r);
    cb->problem.residual(t, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), out);
    ensure_finite(t, out, cb->problem.size, "DAE residual");
  });
}

}  // namespace lagrange::integration
