#pragma once
// RAII owners for SUNDIALS objects. Every SUNDIALS 6 object needs a SUNContext, which must outlive
// them: declare the Context first so it is destroyed last.

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sundials/sundials_linearsolver.h>
#include <sundials/sundials_matrix.h>

#include <memory>
#include <type_traits>

namespace lagrange::integration {

/// Owns a SUNContext (SUNContext_Create / SUNContext_Free).
class Context {
 public:
  /// Creates the context; throws std::runtime_error if SUNDIALS cannot.
  Context();
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  /// The raw context, passed to every SUNDIALS constructor.
  SUNContext get() const { return ctx_; }

 private:
  SUNContext ctx_ = nullptr;
};

/// Deleter for N_Vector (N_VDestroy; a vector made over user data leaves that data alone).
struct VectorDeleter {
  void operator()(N_Vector v) const { N_VDestroy(v); }
};
/// Deleter for SUNMatrix (SUNMatDestroy).
struct MatrixDeleter {
  void operator()(SUNMatrix a) const { SUNMatDestroy(a); }
};
/// Deleter for SUNLinearSolver (SUNLinSolFree).
struct LinearSolverDeleter {
  void operator()(SUNLinearSolver s) const { SUNLinSolFree(s); }
};

using Vector = std::unique_ptr<std::remove_pointer_t<N_Vector>, VectorDeleter>;
using Matrix = std::unique_ptr<std::remove_pointer_t<SUNMatrix>, MatrixDeleter>;
using LinearSolver = std::unique_ptr<std::remove_pointer_t<SUNLinearSolver>, LinearSolverDeleter>;

/// Integrator memory (void*) freed by the package's own function, e.g. CVodeFree(void**).
template <void (*Free)(void**)>
struct MemoryDeleter {
  void operator()(void* mem) const { Free(&mem); }
};
template <void (*Free)(void**)>
using Memory = std::unique_ptr<void, MemoryDeleter<Free>>;

/// A serial N_Vector viewing `data[0..n)` without copying (N_VMake_Serial); `data` must outlive it.
Vector wrap_vector(double* data, size_t n, const Context& ctx);

/// A new serial N_Vector of length n (N_VNew_Serial).
Vector new_vector(size_t n, const Context& ctx);

/// An n×n dense matrix (SUNDenseMatrix).
Matrix dense_matrix(size_t n, const Context& ctx);

/// A dense direct linear solver for `a`, templated on `y` (SUNLinSol_Dense).
LinearSolver dense_solver(N_Vector y, SUNMatrix a, const Context& ctx);

/// An n×n compressed-column sparse matrix with room for `nonzeros` entries (SUNSparseMatrix).
Matrix sparse_matrix(size_t n, size_t nonzeros, const Context& ctx);

/// True when this build has SUNDIALS' KLU sparse direct solver (found at configure time).
bool have_klu();

/// The KLU sparse direct solver for the sparse `a` (SUNLinSol_KLU); only when have_klu().
LinearSolver klu_solver(N_Vector y, SUNMatrix a, const Context& ctx);

/// Returns `mem`, or throws std::runtime_error naming `what` (e.g. "CVodeCreate") if it is null.
void* require_memory(void* mem, const char* what);

}  // namespace lagrange::integration
