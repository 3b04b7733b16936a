// Equilibria and steady states by Newton's method on the exact Jacobian (docs/theory.md §5.5).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lagrange/analysis.hpp"
#include "lagrange/error.hpp"

namespace lagrange {

namespace {

// "theta = 0.1, x = 2, phi_dot = 0.5" for the positions a user can read (plain coordinates and
// body origins) and the non-zero plain rates.
std::string describe(const CompiledModel& cm, const std::vector<double>& q,
                     const std::vector<double>& v) {
  std::string s;
  size_t shown = 0;
  for (size_t i = 0; i < cm.nq && shown < 12; ++i) {
    const std::string& name = cm.coordinate_names[i];
    if (i >= cm.plain && name.find(".R") != std::string::npos) continue;
    s += fmt::format("{}{} = {:.9g}", shown++ ? ", " : "", name, q[i]);
  }
  for (size_t i = 0; i < cm.plain && shown < 16; ++i)
    if (v[i] != 0.0) s += fmt::format(", {} = {:.9g}", cm.velocity_names[i], v[i]);
  return s;
}

struct Residual {
  Eigen::VectorXd a;
  double norm = 0.0;
  bool on_manifold = true;  ///< the projection onto C = 0 converged
};

// a(q, v) after putting q on C = 0 (constrained models; non-free plain coordinates held). The
// projection is given zero rates, so that it moves only q; the held rates are checked against
// Ċ = 0 once trim has converged.
Residual residual_at(Dynamics& dyn, double t, std::vector<double>& q, const std::vector<double>& v,
                     const std::vector<bool>& held) {
  const CompiledModel& cm = dyn.model();
  std::vector<double> qdot(cm.nq), lambda(cm.m);
  Residual r;
  if (cm.m > 0) {
    std::vector<double> still(cm.nv, 0.0);
    r.on_manifold = dyn.try_project(t, q.data(), still.data(), held).converged;
  }
  r.a.resize(static_cast<long>(cm.nv));
  dyn.forward(t, q.data(), v.data(), qdot.data(), r.a.data(), lambda.data());
  r.norm = r.a.norm();
  return r;
}

// A per-coordinate flag vector of options: empty (→ `fallback`) or of size n.
std::vector<bool> flags(const std::vector<bool>& given, size_t n, const char* what,
                        const std::vector<bool>& fallback) {
  if (given.empty()) return fallback;
  if (given.size() != n)
    throw std::invalid_argument(fmt::format("expected {} {} flags, got {}", n, what, given.size()));
  return given;
}

// What trim varies: tangent coordinates (index < nv) and held rates (nv + velocity index).
struct Unknowns {
  std::vector<long> positions, rates;
  size_t size() const { return positions.size() + rates.size(); }
};

Unknowns unknowns_of(const CompiledModel& cm, const TrimOptions& options,
                     std::vector<bool>& steady) {
  const size_t n = cm.nv;
  steady = flags(options.steady, n, "steady", std::vector<bool>(n, false));
  for (size_t i = cm.plain; i < n; ++i)
    if (steady[i])
      throw std::invalid_argument(fmt::format(
          "the rate '{}' of a free body cannot be held: in the body's velocity coordinates a "
          "steady rotation has ω̇ ≠ 0 and r̈ ≠ 0, so a = 0 does not describe it "
          "(docs/theory.md §5.5); write the rotation with angles as coordinates",
          cm.velocity_names[i]));
  std::vector<bool> moving_phase(n, true);
  for (size_t i = 0; i < cm.plain; ++i) moving_phase[i] = !steady[i];
  const std::vector<bool> free = flags(options.free, n, "free", moving_phase);
  const std::vector<bool> rates = flags(options.free_rates, n, "free-rate", std::vector<bool>(n));
  Unknowns u;
  for (size_t i = 0; i < n; ++i) {
    if (free[i]) u.positions.push_back(static_cast<long>(i));
    if (!rates[i]) continue;
    if (!steady[i])
      throw std::invalid_argument(
          fmt::format("the rate '{}' is varied but not held: name it as a steady rate too",
                      cm.velocity_names[i]));
    u.rates.push_back(static_cast<long>(i));
  }
  if (u.size() == 0) throw std::invalid_argument("trim has nothing to vary");
  return u;
}

// What one iteration needs at the current state: the accelerations' Jacobian by the unknowns
// (Af, n × nu) and Z, an orthonormal basis of the directions along the constraint manifold.
struct Linearised {
  Eigen::MatrixXd Af, Z;
};

Linearised linearised_at(const DynamicsJacobian& jac, Dynamics& dyn, double t,
                         const std::vector<double>& q, const std::vector<double>& v,
                         const Unknowns& unknowns, int it) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv), nu = static_cast<long>(unknowns.size()),
             np = static_cast<long>(unknowns.positions.size());
  const StateJacobian J = jac.evaluate(dyn, t, q.data(), v.data());
  const TangentChart chart = tangent_chart(cm, q.data(), v.data());
  const Eigen::SparseMatrix<double> T = chart.T.sparseView();
  const Eigen::MatrixXd Ax = J.a_q * T;
  Linearised L;
  L.Af.resize(n, nu);
  for (long k = 0; k < np; ++k) L.Af.col(k) = Ax.col(unknowns.positions[static_cast<size_t>(k)]);
  for (long k = np; k < nu; ++k)
    L.Af.col(k) = J.a_v.col(unknowns.rates[static_cast<size_t>(k - np)]);
  if (!L.Af.allFinite())
    throw AnalysisError(
        fmt::format("trim: the Jacobian ∂a/∂q is not finite at iteration {} (the dynamics are not "
                    "differentiable there); stopped at {}",
                    it, describe(cm, q, v)));
  // Constrained models: steps move along the manifold, δ = Z ξ with Z an orthonormal basis of
  // the null space of (∂C/∂x)_free (the rates do not enter C); on C = 0 at v = 0, a lies in
  // G's null space too.
  L.Z = Eigen::MatrixXd::Identity(nu, nu);
  if (cm.m > 0) {
    const Eigen::MatrixXd Cx = J.C_q * T;
    Eigen::MatrixXd Cf = Eigen::MatrixXd::Zero(Cx.rows(), nu);
    for (long k = 0; k < np; ++k) Cf.col(k) = Cx.col(unknowns.positions[static_cast<size_t>(k)]);
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> cq(Cf.transpose());
    const Eigen::MatrixXd Q = cq.householderQ();
    L.Z = Q.rightCols(nu - cq.rank());
  }
  return L;
}

// The state after the step δ (positions, then rates) and its residual, or false where the
// dynamics or the projection fail there.
bool try_step(Dynamics& dyn, double t, const Unknowns& unknowns, const Eigen::VectorXd& step,
              const std::vector<bool>& held, TrimResult& state, Residual& r) {
  const CompiledModel& cm = dyn.model();
  const long np = static_cast<long>(unknowns.positions.size());
  std::vector<double> q = state.q, v = state.v;
  Eigen::VectorXd dx = Eigen::VectorXd::Zero(static_cast<long>(cm.nv));
  for (long k = 0; k < np; ++k) dx[unknowns.positions[static_cast<size_t>(k)]] = step[k];
  retract(cm, dx.data(), q.data());
  for (long k = np; k < step.size(); ++k)
    v[static_cast<size_t>(unknowns.rates[static_cast<size_t>(k - np)])] += step[k];
  Residual next;
  try {
    next = residual_at(dyn, t, q, v, held);
  } catch (const SimulationError&) {
    return false;  // a singular point on the way
  }
  if (!std::isfinite(next.norm) || !next.on_manifold) return false;
  state.q = std::move(q);
  state.v = std::move(v);
  r = std::move(next);
  return true;
}

// docs/theory.md §5.5, "Pseudo-transient continuation" (Kelley & Keyes 1998): backward-Euler
// steps of the overdamped flow ξ̇ = Zᵀ a_free along the manifold,
//   (1/Δτ − Zᵀ (∂a/∂x)_free Z) ξ = Zᵀ a_free,   δ = Z ξ,
// with Δτ grown by switched evolution relaxation, Δτ ← Δτ ‖F_prev‖/‖F‖; a step that the
// dynamics refuse, or that grows ‖F‖ a hundredfold, is retried with Δτ/10. As Δτ → ∞ the step
// is Newton's. Positions only (no varied rates). Returns why it failed, or "" on convergence.
std::string pseudo_transient(const DynamicsJacobian& jac, Dynamics& dyn, double t,
                             const Unknowns& unknowns, const std::vector<bool>& held,
                             const TrimOptions& options, TrimResult& result, Residual& r) {
  const long np = static_cast<long>(unknowns.positions.size());
  const auto reduced = [&](const Residual& res, const Eigen::MatrixXd& Z) {
    Eigen::VectorXd af(np);
    for (long k = 0; k < np; ++k) af[k] = res.a[unknowns.positions[static_cast<size_t>(k)]];
    return Eigen::VectorXd(Z.transpose() * af);
  };
  double dtau = options.pseudo_step;
  double previous = -1.0, best = INFINITY;
  int since_best = 0;  // steps with a large Δτ since max |a| last halved
  for (int it = 0;; ++it) {
    result.iterations = it;
    result.residual = r.a.size() ? r.a.cwiseAbs().maxCoeff() : 0.0;
    if (result.residual <= options.tol) return "";
    if (it == options.max_pseudo_steps)
      return fmt::format("{} steps, max |acceleration| = {:.3g}", it, result.residual);
    if (result.residual < 0.5 * best) {
      best = result.residual;
      since_best = 0;
    } else if (dtau > 1e4 * options.pseudo_step && ++since_best == 50) {
      // Only once the steps are nearly Newton's: before that ‖a‖ may rise for a while as the
      // slow modes start to move.
      return fmt::format(
          "stalled: max |acceleration| has not halved in 50 steps, {:.3g} after {} (at the "
          "rounding floor of the accelerations when that is just above the tolerance)",
          result.residual, it);
    }
    const Linearised L = linearised_at(jac, dyn, t, result.q, result.v, unknowns, it);
    Eigen::MatrixXd Aff(np, np);
    for (long k = 0; k < np; ++k) Aff.row(k) = L.Af.row(unknowns.positions[static_cast<size_t>(k)]);
    const Eigen::MatrixXd Jr = L.Z.transpose() * Aff * L.Z;
    const Eigen::VectorXd F = reduced(r, L.Z);
    const double norm = F.norm();
    if (previous > 0.0 && norm > 0.0) dtau = std::min(dtau * previous / norm, 1e300);
    previous = norm;
    bool accepted = false;
    for (int retry = 0; retry < 20 && !accepted; ++retry) {
      const long nr = Jr.rows();
      const Eigen::MatrixXd lhs = Eigen::MatrixXd::Identity(nr, nr) / dtau - Jr;
      const Eigen::VectorXd xi = lhs.partialPivLu().solve(F);
      dtau /= 10.0;  // for the retry, undone below when accepted
      if (!xi.allFinite()) continue;
      TrimResult trial = result;
      Residual next;
      if (!try_step(dyn, t, unknowns, L.Z * xi, held, trial, next)) continue;
      if (next.norm > 100.0 * std::max(r.norm, options.tol)) continue;
      result.q = std::move(trial.q);
      result.v = std::move(trial.v);
      r = std::move(next);
      accepted = true;
      dtau *= 10.0;
    }
    if (!accepted) return fmt::format("no step accepted at step {} down to Δτ = {:.3g}", it, dtau);
  }
}

}  // namespace

TrimResult trim(const DynamicsJacobian& jac, Dynamics& dyn, double t, const std::vector<double>& q0,
                const TrimOptions& options) {
  return trim(jac, dyn, t, q0, std::vector<double>(jac.model().nv, 0.0), options);
}

// docs/theory.md §5.5: solve a(x, v) = 0 for the unknowns u (free tangent coordinates x and
// free held rates): Newton steps (∂a/∂u) Z ξ = −a, δ = Z ξ along the constraint manifold
// (least squares), each shortened by halving until ‖a‖₂ decreases by the Armijo fraction
// 1e-4·s; when that fails from the start, pseudo-transient continuation from the start.
TrimResult trim(const DynamicsJacobian& jac, Dynamics& dyn, double t, const std::vector<double>& q0,
                const std::vector<double>& v0, const TrimOptions& options) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv);
  if (v0.size() != cm.nv)
    throw std::invalid_argument(fmt::format("expected {} velocities, got {}", cm.nv, v0.size()));
  std::vector<bool> steady;
  const Unknowns unknowns = unknowns_of(cm, options, steady);
  const long nu = static_cast<long>(unknowns.size()),
             np = static_cast<long>(unknowns.positions.size());
  std::vector<bool> held(cm.nq, false);
  for (size_t i = 0; i < cm.plain; ++i)
    held[i] = std::find(unknowns.positions.begin(), unknowns.positions.end(),
                        static_cast<long>(i)) == unknowns.positions.end();
  const bool held_rates = std::find(steady.begin(), steady.end(), true) != steady.end();
  const char* what = held_rates ? "steady state" : "equilibrium";
  const auto name_of = [&](long k) {
    return k < np ? tangent_chart(cm, q0.data(), v0.data())
                        .names[static_cast<size_t>(unknowns.positions[static_cast<size_t>(k)])]
                  : cm.velocity_names[static_cast<size_t>(
                        unknowns.rates[static_cast<size_t>(k - np)])];
  };

  TrimResult start;
  start.q = q0;
  start.v.assign(cm.nv, 0.0);
  for (size_t i = 0; i < cm.nv; ++i)
    if (steady[i]) start.v[i] = v0[i];
  const Residual r0 = residual_at(dyn, t, start.q, start.v, held);
  TrimResult result = start;
  Residual r = r0;
  std::string newton_failed;
  for (int it = 0;; ++it) {
    result.iterations = it;
    result.residual = n ? r.a.cwiseAbs().maxCoeff() : 0.0;
    if (result.residual <= options.tol) break;
    if (it == options.max_iterations) {
      newton_failed =
          fmt::format("trim did not converge in {} iterations: max |acceleration| = {:.3g} at {}",
                      options.max_iterations, result.residual, describe(cm, result.q, result.v));
      break;
    }
    const Linearised L = linearised_at(jac, dyn, t, result.q, result.v, unknowns, it);
    const Eigen::MatrixXd Ar = L.Af * L.Z;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Ar);
    qr.setThreshold(1e-10);
    if (qr.rank() < Ar.cols()) {
      // The direction in which the accelerations do not change: what makes it singular.
      const Eigen::MatrixXd N = Eigen::FullPivLU<Eigen::MatrixXd>(Ar).kernel();
      std::string along;
      if (N.cols() > 0 && N.col(0).norm() > 0) {
        Eigen::Index top = 0;
        (L.Z * N.col(0)).cwiseAbs().maxCoeff(&top);
        along = fmt::format(" (the accelerations do not change along '{}')", name_of(top));
      }
      const std::string why = fmt::format(
          "trim: the Jacobian ∂a/∂q is singular at iteration {} (rank {} of {}){}: no isolated "
          "{} here; stopped at {} with max |acceleration| = {:.3g}",
          it, qr.rank(), Ar.cols(), along, what, describe(cm, result.q, result.v), result.residual);
      if (it == 0) throw AnalysisError(why);  // at the start: no isolated root to relax to
      newton_failed = why;
      break;
    }
    const Eigen::VectorXd step = L.Z * qr.solve(Eigen::VectorXd(-r.a));
    double s = 1.0;
    bool accepted = false;
    for (int halving = 0; halving < 30 && !accepted; ++halving, s *= 0.5) {
      TrimResult trial = result;
      Residual next;
      if (!try_step(dyn, t, unknowns, s * step, held, trial, next)) continue;
      if (next.norm <= (1.0 - 1e-4 * s) * r.norm) {
        result.q = std::move(trial.q);
        result.v = std::move(trial.v);
        r = std::move(next);
        accepted = true;
      }
    }
    if (!accepted) {
      newton_failed = fmt::format(
          "trim: no step along the Newton direction reduces the accelerations at iteration {} "
          "(a local minimum of |a| that is not {}{}); stopped at {} with max "
          "|acceleration| = {:.3g}",
          it, held_rates ? "a steady state" : "an equilibrium",
          nu < n ? ", or none with these coordinates free" : "", describe(cm, result.q, result.v),
          result.residual);
      break;
    }
  }
  if (!newton_failed.empty()) {
    if (!unknowns.rates.empty() || options.max_pseudo_steps <= 0)
      throw AnalysisError(newton_failed);
    TrimResult relaxed = start;
    Residual rr = r0;
    const std::string why = pseudo_transient(jac, dyn, t, unknowns, held, options, relaxed, rr);
    if (!why.empty())
      throw AnalysisError(fmt::format(
          "{}; pseudo-transient continuation from the start failed too ({}), stopped at {}",
          newton_failed, why, describe(cm, relaxed.q, relaxed.v)));
    result = std::move(relaxed);
    result.pseudo_transient = true;
  }
  if (!held_rates) return result;
  // docs/theory.md §5.5: a held rate must keep the constraints (Ċ = G v = 0), and the motion
  // q₀ + v t stays steady to first order when ȧ = ∂a/∂q q̇ vanishes.
  if (cm.m > 0) {
    std::vector<double> C(cm.m), Cdot(cm.m);
    dyn.constraints(t, result.q.data(), result.v.data(), C.data(), Cdot.data());
    double worst = 0.0;
    for (double c : Cdot) worst = std::max(worst, std::abs(c));
    if (worst > options.tol)
      throw AnalysisError(fmt::format(
          "trim: the held rates move the constraints (max |Ċ| = {:.3g} at {}): no steady state "
          "with these rates and the other velocities 0",
          worst, describe(cm, result.q, result.v)));
  }
  const StateJacobian J = jac.evaluate(dyn, t, result.q.data(), result.v.data());
  result.drift = n ? (J.a_q * J.qdot).cwiseAbs().maxCoeff() : 0.0;
  return result;
}

}  // namespace lagrange
