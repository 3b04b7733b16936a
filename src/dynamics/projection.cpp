#include <fmt/format.h>

#include <Eigen/QR>
#include <cmath>

#include "lagrange/dynamics.hpp"
#include "lagrange/error.hpp"

namespace lagrange {

namespace {

double max_abs(const double* x, size_t n) {
  double r = 0.0;
  for (size_t i = 0; i < n; ++i) r = std::max(r, std::abs(x[i]));
  return r;
}

}  // namespace

// DESIGN.md §4.3, consistent initial state: the least-squares (minimum-norm) change of the
// free coordinates that satisfies C = 0 (Gauss–Newton on the linearisation G Δq = −C), then
// the minimum-norm change of the free rates that satisfies Ċ = G v + ∂ₜC = 0.
ProjectionResult Dynamics::project(double t, double* q, double* v, const std::vector<bool>& fixed,
                                   double tol, int max_iterations) {
  const CompiledModel& cm = *model_;
  ProjectionResult res;
  if (cm.m == 0) return res;
  const long n = static_cast<long>(cm.n), m = static_cast<long>(cm.m);
  Eigen::Map<Eigen::VectorXd> qv(q, n), vv(v, n);
  const Eigen::VectorXd q_start = qv, v_start = vv;
  Eigen::VectorXd rhs(m);
  auto free_jacobian = [&]() {
    assemble_G();
    Eigen::MatrixXd Gf = G_;
    for (long j = 0; j < n; ++j)
      if (static_cast<size_t>(j) < fixed.size() && fixed[static_cast<size_t>(j)])
        Gf.col(j).setZero();
    return Gf;
  };
  for (;; ++res.iterations) {
    eval_dynamics(t, q, v);
    res.residual = max_abs(out_.data() + cm.C_out(), cm.m);
    if (!std::isfinite(res.residual))
      throw SimulationError(t, "the constraints are not finite at the initial state");
    if (res.residual <= tol) break;
    if (res.iterations >= max_iterations)
      throw SimulationError(
          t, fmt::format("projection onto the constraints did not converge in {} iterations "
                         "(max |C| = {:.3g}); the initial state may be far from any consistent "
                         "state, or the free coordinates cannot satisfy the constraints",
                         max_iterations, res.residual));
    for (long r = 0; r < m; ++r) rhs[r] = -out_[cm.C_out() + static_cast<size_t>(r)];
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(free_jacobian());
    qv += cod.solve(rhs);
  }
  eval_dynamics(t, q, v);
  for (long r = 0; r < m; ++r) rhs[r] = -out_[cm.Cdot_out() + static_cast<size_t>(r)];
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(free_jacobian());
  vv += cod.solve(rhs);
  eval_dynamics(t, q, v);
  res.rate_residual = max_abs(out_.data() + cm.Cdot_out(), cm.m);
  res.position_change = (qv - q_start).norm();
  res.velocity_change = (vv - v_start).norm();
  return res;
}

}  // namespace lagrange
