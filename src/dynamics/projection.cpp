#include <fmt/format.h>

#include <Eigen/QR>
#include <Eigen/SparseCholesky>
#include <cmath>
#include <limits>

#include "dynamics/rounding_floor.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/error.hpp"

namespace lagrange {

namespace {

double max_abs(const double* x, size_t n) {
  double r = 0.0;
  for (size_t i = 0; i < n; ++i) r = std::max(r, std::abs(x[i]));
  return r;
}

// docs/theory.md §4.3, "Projecting when the drift matters": the minimum-norm solution of
// J x = rhs, x = Jᵀ (J Jᵀ)⁻¹ rhs, from a sparse LDLᵀ of J Jᵀ — constraint Jacobians have a few
// non-zeros a row, so this costs O(non-zeros) where a dense QR of J costs O(m² n). The normal
// equations square J's condition number, which the Gauss–Newton iteration around it absorbs
// (each step only has to reduce C); when J Jᵀ is (nearly) singular — redundant constraints —
// the rank-revealing complete orthogonal decomposition of J answers instead.
Eigen::VectorXd min_norm_solve(const Eigen::MatrixXd& J, const Eigen::VectorXd& rhs) {
  const Eigen::SparseMatrix<double> Js = J.sparseView();
  const Eigen::SparseMatrix<double> JJt = Js * Js.transpose();
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(JJt);
  if (ldlt.info() == Eigen::Success && JJt.rows() > 0) {
    const Eigen::VectorXd d = ldlt.vectorD();
    if (d.minCoeff() > 1e-12 * d.maxCoeff()) return Js.transpose() * ldlt.solve(rhs);
  }
  return Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(J).solve(rhs);
}

// A Gauss–Newton step for (∂C/∂q) Δq = rhs that moves each free body's R along SO(3): R's nine
// columns of J give way to three, ∂C/∂θ_k = Σ_ij J_{R_ij} (R [e_k]×)_ij, and the minimum-norm
// solution in those coordinates maps back to ΔR = R [Δθ]×, tangent to SO(3) (its distance from
// SO(3) is then of the order of |Δθ|², not |Δθ|).
Eigen::VectorXd tangent_step(const Eigen::MatrixXd& J, const Eigen::VectorXd& rhs,
                             const Eigen::VectorXd& q, const std::vector<size_t>& rotations) {
  if (rotations.empty()) return min_norm_solve(J, rhs);
  const long nq = J.cols();
  std::vector<long> plain;  // columns of q outside every R
  std::vector<bool> in_rotation(static_cast<size_t>(nq), false);
  for (const size_t o : rotations)
    for (size_t e = 0; e < 9; ++e) in_rotation[o + e] = true;
  for (long j = 0; j < nq; ++j)
    if (!in_rotation[static_cast<size_t>(j)]) plain.push_back(j);
  const long np = static_cast<long>(plain.size()), nr = 3 * static_cast<long>(rotations.size());
  // dR/dθ_k = R [e_k]×, row-major: column c of R [e_k]× is R times column c of [e_k]×.
  auto tangent = [&](size_t o, int k) {
    Eigen::Matrix3d R;
    for (int i = 0; i < 3; ++i)
      for (int c = 0; c < 3; ++c) R(i, c) = q[static_cast<long>(o) + 3 * i + c];
    Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
    const int a = (k + 1) % 3, b = (k + 2) % 3;
    E(b, a) = 1;
    E(a, b) = -1;
    return Eigen::Matrix3d(R * E);
  };
  Eigen::MatrixXd Jr(J.rows(), np + nr);
  for (long c = 0; c < np; ++c) Jr.col(c) = J.col(plain[static_cast<size_t>(c)]);
  for (size_t b = 0; b < rotations.size(); ++b)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix3d T = tangent(rotations[b], k);
      Eigen::VectorXd col = Eigen::VectorXd::Zero(J.rows());
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c)
          col += T(i, c) * J.col(static_cast<long>(rotations[b]) + 3 * i + c);
      Jr.col(np + 3 * static_cast<long>(b) + k) = col;
    }
  const Eigen::VectorXd x = min_norm_solve(Jr, rhs);
  Eigen::VectorXd step = Eigen::VectorXd::Zero(nq);
  for (long c = 0; c < np; ++c) step[plain[static_cast<size_t>(c)]] = x[c];
  for (size_t b = 0; b < rotations.size(); ++b)
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix3d T = tangent(rotations[b], k);
      for (int i = 0; i < 3; ++i)
        for (int c = 0; c < 3; ++c)
          step[static_cast<long>(rotations[b]) + 3 * i + c] +=
              x[np + 3 * static_cast<long>(b) + k] * T(i, c);
    }
  return step;
}

}  // namespace

// docs/theory.md §4.3, consistent initial state: the least-squares (minimum-norm) change of the
// free coordinates that satisfies C = 0 (Gauss–Newton on the linearisation (∂C/∂q) Δq = −C,
// each step halved until ‖C‖₂ decreases, so that the residual never grows), then the
// minimum-norm change of the free velocities that satisfies Ċ = G v + … = 0. A free body's R
// moves along SO(3) (tangent_step), so that a constraint on a body point does not push R off
// it by the size of the correction. Stops without
// converging when no halving of the step reduces ‖C‖₂, e.g. at a least-squares minimum where
// C ≠ 0 (or fixed coordinates in the way) or after max_iterations, at the state of least ‖C‖₂
// found. A residual at the rounding floor of C's terms counts as converged whatever `tol` asks.
ProjectionResult Dynamics::try_project(double t, double* q, double* v,
                                       const std::vector<bool>& fixed, double tol,
                                       int max_iterations) {
  const CompiledModel& cm = *model_;
  ProjectionResult res;
  res.converged = true;
  if (cm.m == 0) return res;
  constexpr int kHalvings = 30;
  const long nq = static_cast<long>(cm.nq), nv = static_cast<long>(cm.nv),
             m = static_cast<long>(cm.m);
  Eigen::Map<Eigen::VectorXd> qv(q, nq), vv(v, nv);
  const Eigen::VectorXd q_start = qv, v_start = vv;
  Eigen::VectorXd rhs(m);
  auto is_fixed = [&](size_t j) { return j < fixed.size() && fixed[j]; };
  auto position_jacobian = [&]() {
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(m, nq);
    const double* d = out_.data() + cm.Cq_out();
    for (size_t e = 0; e < cm.Cq_pattern.size(); ++e)
      if (!is_fixed(cm.Cq_pattern[e].second))
        J(static_cast<long>(cm.Cq_pattern[e].first), static_cast<long>(cm.Cq_pattern[e].second)) =
            d[e];
    return J;
  };
  auto velocity_jacobian = [&]() {  // plain velocities share their coordinate's flag
    assemble_G();
    Eigen::MatrixXd Gf = G_;
    for (long k = 0; k < nv; ++k)
      if (static_cast<size_t>(k) < cm.plain && is_fixed(static_cast<size_t>(k)))
        Gf.col(k).setZero();
    return Gf;
  };
  auto norm_C = [&]() {
    return Eigen::Map<const Eigen::VectorXd>(out_.data() + cm.C_out(), m).norm();
  };
  eval_dynamics(t, q, v);
  for (;; ++res.iterations) {
    res.residual = max_abs(out_.data() + cm.C_out(), cm.m);
    if (!std::isfinite(res.residual))
      throw SimulationError(t, "the constraints are not finite at the initial state");
    const Eigen::MatrixXd J = position_jacobian();
    if (res.residual <= std::max(tol, rounding_floor(J, qv))) break;
    if (res.iterations >= max_iterations) {
      res.converged = false;
      break;
    }
    for (long r = 0; r < m; ++r) rhs[r] = -out_[cm.C_out() + static_cast<size_t>(r)];
    const Eigen::VectorXd step = tangent_step(J, rhs, qv, cm.rotations);
    const Eigen::VectorXd q_here = qv;
    const double here = norm_C();
    double scale = 1.0;
    int halvings = 0;
    for (;; ++halvings, scale /= 2) {
      qv = q_here + scale * step;
      eval_dynamics(t, q, v);
      const double there = norm_C();
      if (there < here) break;  // false for NaN too: a step into a pole is halved
      if (halvings == kHalvings) break;
    }
    if (halvings == kHalvings) {  // no descent along the Gauss–Newton direction
      qv = q_here;
      eval_dynamics(t, q, v);
      res.residual = max_abs(out_.data() + cm.C_out(), cm.m);
      res.converged = res.residual <= std::max(tol, rounding_floor(position_jacobian(), qv));
      break;
    }
  }
  for (long r = 0; r < m; ++r) rhs[r] = -out_[cm.Cdot_out() + static_cast<size_t>(r)];
  const Eigen::MatrixXd Gf = velocity_jacobian();
  vv += min_norm_solve(Gf, rhs);
  eval_dynamics(t, q, v);
  res.rate_residual = max_abs(out_.data() + cm.Cdot_out(), cm.m);
  res.floor = rounding_floor(position_jacobian(), qv);
  res.rate_floor = rounding_floor(Gf, vv);
  res.position_change = (qv - q_start).norm();
  res.velocity_change = (vv - v_start).norm();
  return res;
}

ProjectionResult Dynamics::project(double t, double* q, double* v, const std::vector<bool>& fixed,
                                   double tol, int max_iterations) {
  const ProjectionResult res = try_project(t, q, v, fixed, tol, max_iterations);
  if (!res.converged)
    throw SimulationError(
        t, fmt::format("projection onto the constraints did not converge in {} iterations "
                       "(max |C| = {:.3g}); the state may be far from any consistent state, or "
                       "the free coordinates cannot satisfy the constraints",
                       res.iterations, res.residual));
  return res;
}

}  // namespace lagrange
