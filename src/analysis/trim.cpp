// Equilibria by Newton's method on the exact Jacobian (docs/theory.md §5.5).

#include <fmt/format.h>

#include <cmath>

#include "lagrange/analysis.hpp"
#include "lagrange/error.hpp"

namespace lagrange {

namespace {

// "theta = 0.1, x = 2" for the positions a user can read (plain coordinates and body origins).
std::string describe(const CompiledModel& cm, const std::vector<double>& q) {
  std::string s;
  size_t shown = 0;
  for (size_t i = 0; i < cm.nq && shown < 12; ++i) {
    const std::string& name = cm.coordinate_names[i];
    if (i >= cm.plain && name.find(".R") != std::string::npos) continue;
    s += fmt::format("{}{} = {:.9g}", shown++ ? ", " : "", name, q[i]);
  }
  return s;
}

struct Residual {
  Eigen::VectorXd a;
  double norm = 0.0;
};

// a(q, v = 0) after putting q on C = 0 (constrained models; non-free plain coordinates held).
Residual residual_at(Dynamics& dyn, double t, std::vector<double>& q,
                     const std::vector<bool>& held) {
  const CompiledModel& cm = dyn.model();
  std::vector<double> v(cm.nv, 0.0), qdot(cm.nq), lambda(cm.m);
  if (cm.m > 0) (void)dyn.try_project(t, q.data(), v.data(), held);
  Residual r;
  r.a.resize(static_cast<long>(cm.nv));
  dyn.forward(t, q.data(), v.data(), qdot.data(), r.a.data(), lambda.data());
  r.norm = r.a.norm();
  return r;
}

}  // namespace

// docs/theory.md §5.5: solve a(x, v = 0) = 0 for the free tangent coordinates x: Newton steps
// (∂a/∂x)_free Z ξ = −a, δ = Z ξ along the constraint manifold (least squares), each shortened
// by halving until ‖a‖₂ decreases by the Armijo fraction 1e-4·s.
TrimResult trim(const DynamicsJacobian& jac, Dynamics& dyn, double t, const std::vector<double>& q0,
                const TrimOptions& options) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv);
  std::vector<bool> free = options.free.empty() ? std::vector<bool>(cm.nv, true) : options.free;
  if (free.size() != cm.nv)
    throw std::invalid_argument(fmt::format("expected {} free flags, got {}", cm.nv, free.size()));
  std::vector<long> unknowns;
  for (long i = 0; i < n; ++i)
    if (free[static_cast<size_t>(i)]) unknowns.push_back(i);
  std::vector<bool> held(cm.nq, false);
  for (size_t i = 0; i < cm.plain; ++i) held[i] = !free[i];

  TrimResult result;
  result.q = q0;
  result.v.assign(cm.nv, 0.0);
  Residual r = residual_at(dyn, t, result.q, held);
  for (int it = 0;; ++it) {
    result.iterations = it;
    result.residual = n ? r.a.cwiseAbs().maxCoeff() : 0.0;
    if (result.residual <= options.tol) return result;
    if (it == options.max_iterations)
      throw AnalysisError(
          fmt::format("trim did not converge in {} iterations: max |acceleration| = {:.3g} at {}",
                      options.max_iterations, result.residual, describe(cm, result.q)));
    const StateJacobian J = jac.evaluate(dyn, t, result.q.data(), result.v.data());
    const TangentChart chart = tangent_chart(cm, result.q.data(), result.v.data());
    const Eigen::MatrixXd Ax = J.a_q * chart.T;
    Eigen::MatrixXd Af(n, static_cast<long>(unknowns.size()));
    for (size_t k = 0; k < unknowns.size(); ++k) Af.col(static_cast<long>(k)) = Ax.col(unknowns[k]);
    if (!Af.allFinite())
      throw AnalysisError(fmt::format(
          "trim: the Jacobian ∂a/∂q is not finite at iteration {} (the dynamics are not "
          "differentiable there); stopped at {}",
          it, describe(cm, result.q)));
    // Constrained models: Newton moves along the manifold, δ = Z ξ with Z an orthonormal basis
    // of the null space of (∂C/∂x)_free; on C = 0 at v = 0, a lies in G's null space too.
    Eigen::MatrixXd Z = Eigen::MatrixXd::Identity(Af.cols(), Af.cols());
    if (cm.m > 0) {
      const Eigen::MatrixXd Cx = J.C_q * chart.T;
      Eigen::MatrixXd Cf(Cx.rows(), Af.cols());
      for (size_t k = 0; k < unknowns.size(); ++k)
        Cf.col(static_cast<long>(k)) = Cx.col(unknowns[k]);
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> cq(Cf.transpose());
      const Eigen::MatrixXd Q = cq.householderQ();
      Z = Q.rightCols(Af.cols() - cq.rank());
    }
    const Eigen::MatrixXd Ar = Af * Z;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Ar);
    qr.setThreshold(1e-10);
    if (qr.rank() < Ar.cols()) {
      // The direction in which the accelerations do not change: what makes it singular.
      const Eigen::MatrixXd N = Eigen::FullPivLU<Eigen::MatrixXd>(Ar).kernel();
      std::string along;
      if (N.cols() > 0 && N.col(0).norm() > 0) {
        Eigen::Index top = 0;
        (Z * N.col(0)).cwiseAbs().maxCoeff(&top);
        along = fmt::format(" (the accelerations do not change along '{}')",
                            chart.names[static_cast<size_t>(unknowns[static_cast<size_t>(top)])]);
      }
      throw AnalysisError(fmt::format(
          "trim: the Jacobian ∂a/∂q is singular at iteration {} (rank {} of {}){}: no isolated "
          "equilibrium here; stopped at {} with max |acceleration| = {:.3g}",
          it, qr.rank(), Ar.cols(), along, describe(cm, result.q), result.residual));
    }
    const Eigen::VectorXd step = Z * qr.solve(Eigen::VectorXd(-r.a));
    Eigen::VectorXd dx = Eigen::VectorXd::Zero(n);
    for (size_t k = 0; k < unknowns.size(); ++k) dx[unknowns[k]] = step[static_cast<long>(k)];
    double s = 1.0;
    bool accepted = false;
    for (int halving = 0; halving < 30 && !accepted; ++halving, s *= 0.5) {
      std::vector<double> q = result.q;
      const Eigen::VectorXd ds = s * dx;
      retract(cm, ds.data(), q.data());
      Residual next;
      try {
        next = residual_at(dyn, t, q, held);
      } catch (const SimulationError&) {
        continue;  // a singular point on the way: shorten the step
      }
      if (std::isfinite(next.norm) && next.norm <= (1.0 - 1e-4 * s) * r.norm) {
        result.q = std::move(q);
        r = std::move(next);
        accepted = true;
      }
    }
    if (!accepted)
      throw AnalysisError(fmt::format(
          "trim: no step along the Newton direction reduces the accelerations at iteration {} "
          "(a local minimum of |a| that is not an equilibrium{}); stopped at {} with max "
          "|acceleration| = {:.3g}",
          it,
          unknowns.size() < static_cast<size_t>(n) ? ", or none with these coordinates free" : "",
          describe(cm, result.q), result.residual));
  }
}

}  // namespace lagrange
