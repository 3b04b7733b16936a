#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "dynamics/projection_workspace.hpp"
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

double distance(const double* x, const double* y, size_t n) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += (x[i] - y[i]) * (x[i] - y[i]);
  return std::sqrt(s);
}

}  // namespace

// docs/theory.md §4.3, consistent initial state: the least-squares (minimum-norm) change of the
// free coordinates that satisfies C = 0 (Gauss–Newton on the linearisation (∂C/∂q) Δq = −C,
// each step halved until ‖C‖₂ decreases, so that the residual never grows), then the
// minimum-norm change of the free velocities that satisfies Ċ = G v + … = 0. A free body's R
// moves along SO(3) (TangentJacobian), so that a constraint on a body point does not push R off
// it by the size of the correction. Stops without
// converging when no halving of the step reduces ‖C‖₂, e.g. at a least-squares minimum where
// C ≠ 0 (or fixed coordinates in the way) or after max_iterations, at the state of least ‖C‖₂
// found. A residual at the rounding floor of C's terms counts as converged whatever `tol` asks.
// The sparse structure of both minimum-norm problems is set up by the first call; later calls
// only compute (docs/theory.md §4.3, "The KKT solve without per-call overhead").
ProjectionResult Dynamics::try_project(double t, double* q, double* v,
                                       const std::vector<bool>& fixed, double tol,
                                       int max_iterations) {
  const CompiledModel& cm = *model_;
  ProjectionResult res;
  res.converged = true;
  if (cm.m == 0) return res;
  if (!projection_) projection_ = std::make_unique<dynamics::ProjectionWorkspace>(cm);
  dynamics::ProjectionWorkspace& w = *projection_;
  constexpr int kHalvings = 30;
  const size_t nq = cm.nq, nv = cm.nv, m = cm.m;
  std::copy(q, q + nq, w.q_start.begin());
  std::copy(v, v + nv, w.v_start.begin());
  auto is_fixed = [&](size_t j) { return j < fixed.size() && fixed[j]; };
  // ∂C/∂q of the last evaluation, the fixed coordinates' columns zeroed, and its rounding floor.
  auto position_floor = [&]() {
    const double* d = out_.data() + cm.Cq_out();
    for (size_t e = 0; e < cm.Cq_pattern.size(); ++e)
      w.cq[e] = is_fixed(cm.Cq_pattern[e].second) ? 0.0 : d[e];
    return rounding_floor(cm.Cq_pattern, w.cq.data(), q, w.terms);
  };
  auto norm_C = [&]() {
    return Eigen::Map<const Eigen::VectorXd>(out_.data() + cm.C_out(), static_cast<long>(m)).norm();
  };
  eval_dynamics(t, q, v);
  for (;; ++res.iterations) {
    res.residual = max_abs(out_.data() + cm.C_out(), m);
    if (!std::isfinite(res.residual))
      throw SimulationError(t, "the constraints are not finite at the initial state");
    if (res.residual <= std::max(tol, position_floor())) break;
    if (res.iterations >= max_iterations) {
      res.converged = false;
      break;
    }
    for (size_t r = 0; r < m; ++r) w.rhs[r] = -out_[cm.C_out() + r];
    w.tangent.reduce(w.cq.data(), q, w.reduced.data());
    w.positions.solve(w.reduced.data(), w.rhs.data(), w.x.data());
    w.tangent.expand(w.x.data(), q, w.step.data());
    std::copy(q, q + nq, w.q_here.begin());
    const double here = norm_C();
    double scale = 1.0;
    int halvings = 0;
    for (;; ++halvings, scale /= 2) {
      for (size_t j = 0; j < nq; ++j) q[j] = w.q_here[j] + scale * w.step[j];
      eval_dynamics(t, q, v);
      const double there = norm_C();
      if (there < here) break;  // false for NaN too: a step into a pole is halved
      if (halvings == kHalvings) break;
    }
    if (halvings == kHalvings) {  // no descent along the Gauss–Newton direction
      std::copy(w.q_here.begin(), w.q_here.end(), q);
      eval_dynamics(t, q, v);
      res.residual = max_abs(out_.data() + cm.C_out(), m);
      res.converged = res.residual <= std::max(tol, position_floor());
      break;
    }
  }
  // G with the fixed plain coordinates' velocities zeroed (they share their coordinate's flag).
  for (size_t r = 0; r < m; ++r) w.rhs[r] = -out_[cm.Cdot_out() + r];
  const double* g = out_.data() + cm.G_out();
  for (size_t e = 0; e < cm.G_pattern.size(); ++e) {
    const size_t k = cm.G_pattern[e].second;
    w.g[e] = k < cm.plain && is_fixed(k) ? 0.0 : g[e];
  }
  w.velocities.solve(w.g.data(), w.rhs.data(), w.dv.data());
  for (size_t k = 0; k < nv; ++k) v[k] += w.dv[k];
  eval_dynamics(t, q, v);
  res.rate_residual = max_abs(out_.data() + cm.Cdot_out(), m);
  res.floor = position_floor();
  res.rate_floor = rounding_floor(cm.G_pattern, w.g.data(), v, w.terms);
  res.position_change = distance(q, w.q_start.data(), nq);
  res.velocity_change = distance(v, w.v_start.data(), nv);
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
