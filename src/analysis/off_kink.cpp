#include "analysis/off_kink.hpp"

namespace lagrange::analysis_detail {

namespace {

bool finite(const ImplicitJacobian& J) {
  const auto ok = [](const Eigen::SparseMatrix<double>& A) {
    return all_finite(A.valuePtr(), A.valuePtr() + A.nonZeros());
  };
  return ok(J.K) && ok(J.Phi_x) && ok(J.qdot_x);
}

}  // namespace

// docs/theory.md §5.6: the one-sided derivatives at a kink, as for the first-order form.
ImplicitJacobian implicit_off_kink(const DynamicsJacobian& jac, Dynamics& dyn, double t,
                                   const double* y, const double* a, const double* lambda) {
  const size_t nq = jac.model().nq, n = nq + jac.model().nv;
  ImplicitJacobian J = jac.implicit(dyn, t, y, y + nq, a, lambda);
  if (finite(J)) return J;  // the common case: no generator to seed
  std::mt19937 random(5);
  for (int attempt = 0; attempt < 3 && !finite(J); ++attempt) {
    const std::vector<double> moved = off_kink(y, n, random);
    J = jac.implicit(dyn, t, moved.data(), moved.data() + nq, a, lambda);
  }
  return J;
}

}  // namespace lagrange::analysis_detail
