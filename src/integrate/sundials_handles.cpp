#include "integrate/sundials_handles.hpp"

#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#ifdef LAGRANGE_HAVE_KLU
#include <sunlinsol/sunlinsol_klu.h>
#endif

#include <stdexcept>
#include <string>

namespace lagrange::integration {

namespace {

/// Throws std::runtime_error when a SUNDIALS constructor returned null.
template <class T>
T not_null(T object, const char* what) {
  if (object == nullptr) throw std::runtime_error(std::string("SUNDIALS: ") + what + " failed");
  return object;
}

}  // namespace

Context::Context() {
  if (SUNContext_Create(nullptr, &ctx_) != 0 || ctx_ == nullptr) {
    throw std::runtime_error("SUNDIALS: SUNContext_Create failed");
  }
}

Context::~Context() {
  SUNContext_Free(&ctx_);
}

Vector wrap_vector(double* data, size_t n, const Context& ctx) {
  return Vector(
      not_null(N_VMake_Serial(static_cast<sunindextype>(n), data, ctx.get()), "N_VMake_Serial"));
}

Vector new_vector(size_t n, const Context& ctx) {
  return Vector(not_null(N_VNew_Serial(static_cast<sunindextype>(n), ctx.get()), "N_VNew_Serial"));
}

Matrix dense_matrix(size_t n, const Context& ctx) {
  const auto m = static_cast<sunindextype>(n);
  return Matrix(not_null(SUNDenseMatrix(m, m, ctx.get()), "SUNDenseMatrix"));
}

LinearSolver dense_solver(N_Vector y, SUNMatrix a, const Context& ctx) {
  return LinearSolver(not_null(SUNLinSol_Dense(y, a, ctx.get()), "SUNLinSol_Dense"));
}

Matrix sparse_matrix(size_t n, size_t nonzeros, const Context& ctx) {
  const auto m = static_cast<sunindextype>(n);
  return Matrix(
      not_null(SUNSparseMatrix(m, m, static_cast<sunindextype>(nonzeros), CSC_MAT, ctx.get()),
               "SUNSparseMatrix"));
}

bool have_klu() {
#ifdef LAGRANGE_HAVE_KLU
  return true;
#else
  return false;
#endif
}

LinearSolver klu_solver(N_Vector y, SUNMatrix a, const Context& ctx) {
#ifdef LAGRANGE_HAVE_KLU
  return LinearSolver(not_null(SUNLinSol_KLU(y, a, ctx.get()), "SUNLinSol_KLU"));
#else
  throw std::logic_error("SUNDIALS: this build has no KLU (libsuitesparse-dev)");
#endif
}

void* require_memory(void* mem, const char* what) {
  return not_null(mem, what);
}

}  // namespace lagrange::integration
