#include "integrate/callbacks.hpp"

#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <algorithm>

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

namespace {

/// A matrix given by its compressed-column pattern and values into a sparse (same pattern) or
/// dense SUNMatrix J of size n.
void write_matrix(SUNMatrix J, size_t n, const std::vector<long>& column_starts,
                  const std::vector<long>& rows, const std::vector<double>& values) {
  if (SUNMatGetID(J) == SUNMATRIX_SPARSE) {
    sunindextype* starts = SUNSparseMatrix_IndexPointers(J);
    sunindextype* index = SUNSparseMatrix_IndexValues(J);
    for (size_t j = 0; j <= n; ++j) starts[j] = column_starts[j];
    std::copy(rows.begin(), rows.end(), index);
    std::copy(values.begin(), values.end(), SUNSparseMatrix_Data(J));
    return;
  }
  SUNMatZero(J);
  for (size_t j = 0; j < n; ++j) {
    double* column = SUNDenseMatrix_Column(J, static_cast<sunindextype>(j));
    for (long e = column_starts[j]; e < column_starts[j + 1]; ++e)
      column[rows[static_cast<size_t>(e)]] = values[static_cast<size_t>(e)];
  }
}

}  // namespace

int OdeCallback::jacobian(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* self,
                          N_Vector /*tmp1*/, N_Vector /*tmp2*/, N_Vector /*tmp3*/) {
  auto* cb = static_cast<OdeCallback*>(self);
  return cb->guard.run([&] {
    const OdeJacobian& jac = cb->problem.jacobian;
    cb->values.resize(jac.nonzeros());
    jac.values(t, N_VGetArrayPointer(y), cb->values.data());
    ensure_finite(t, cb->values.data(), cb->values.size(), "Jacobian");
    write_matrix(J, cb->problem.size, jac.column_starts, jac.rows, cb->values);
  });
}

int DaeCallback::jacobian(sunrealtype t, sunrealtype cj, N_Vector y, N_Vector yp, N_Vector /*r*/,
                          SUNMatrix J, void* self, N_Vector /*tmp1*/, N_Vector /*tmp2*/,
                          N_Vector /*tmp3*/) {
  auto* cb = static_cast<DaeCallback*>(self);
  return cb->guard.run([&] {
    const DaeJacobian& jac = cb->problem.jacobian;
    cb->values.resize(jac.nonzeros());
    jac.values(t, cj, N_VGetArrayPointer(y), N_VGetArrayPointer(yp), cb->values.data());
    ensure_finite(t, cb->values.data(), cb->values.size(), "Newton matrix");
    write_matrix(J, cb->problem.size, jac.column_starts, jac.rows, cb->values);
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
