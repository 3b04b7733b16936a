// Equilibria and steady states by Newton's method on the exact Jacobian (docs/theory.md §5.5).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "dynamics/rounding_floor.hpp"
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

// A free input of trim: a model input (held by Dynamics::hold_input) or a parameter
// (Dynamics::set_parameters), by its index among those.
struct FreeInput {
  bool parameter = false;
  size_t index = 0;
  long column = 0;  ///< its column of ∂a/∂w (DynamicsJacobian::input_names)
};

// What trim varies: tangent coordinates and held rates (indices < nv), then free inputs; the
// step's entries come in that order.
struct Unknowns {
  std::vector<long> positions, rates;
  std::vector<FreeInput> inputs;
  size_t size() const { return positions.size() + rates.size() + inputs.size(); }
};

// The current values of the free inputs in `dyn` (model inputs as its last evaluation saw them).
std::vector<double> input_values(Dynamics& dyn, const Unknowns& u, double t,
                                 const std::vector<double>& q, const std::vector<double>& v) {
  const CompiledModel& cm = dyn.model();
  std::vector<double> qdot(cm.nq), a(cm.nv), lambda(cm.m), values;
  if (!u.inputs.empty()) dyn.forward(t, q.data(), v.data(), qdot.data(), a.data(), lambda.data());
  for (const FreeInput& in : u.inputs)
    values.push_back(in.parameter ? dyn.parameters()[in.index]
                                  : dyn.last_inputs()[cm.u_offset() + in.index]);
  return values;
}

void set_inputs(Dynamics& dyn, const Unknowns& u, const std::vector<double>& values) {
  if (u.inputs.empty()) return;
  std::vector<double> params = dyn.parameters();
  bool changed = false;
  for (size_t k = 0; k < u.inputs.size(); ++k) {
    const FreeInput& in = u.inputs[k];
    if (!in.parameter) {
      dyn.hold_input(in.index, values[k]);
    } else if (params[in.index] != values[k]) {
      params[in.index] = values[k];
      changed = true;
    }
  }
  if (changed) dyn.set_parameters(params);
}

Unknowns unknowns_of(const DynamicsJacobian& jac, const TrimOptions& options,
                     std::vector<bool>& steady) {
  const CompiledModel& cm = jac.model();
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
  const std::vector<std::string>& names = jac.input_names();
  const std::vector<bool> inputs =
      flags(options.free_inputs, names.size(), "free-input", std::vector<bool>(names.size()));
  for (size_t j = 0; j < names.size(); ++j) {
    if (!inputs[j]) continue;
    FreeInput in;
    in.column = static_cast<long>(j);
    const auto p = std::find(cm.parameter_names.begin(), cm.parameter_names.end(), names[j]);
    in.parameter = p != cm.parameter_names.end();
    in.index = static_cast<size_t>(
        in.parameter ? p - cm.parameter_names.begin()
                     : std::find(cm.input_names.begin(), cm.input_names.end(), names[j]) -
                           cm.input_names.begin());
    u.inputs.push_back(in);
  }
  if (u.size() == 0) throw std::invalid_argument("trim has nothing to vary");
  return u;
}

/// The largest rounding floor trim accepts, relative to the accelerations' change per unit
/// coordinate (docs/theory.md §5.5, "Tolerance").
constexpr double kFloorCap = 1e-6;

// What one iteration needs at the current state: the accelerations' Jacobian by the unknowns
// (Af, n × nu) and Z, an orthonormal basis of the directions along the constraint manifold.
struct Linearised {
  Eigen::MatrixXd Af, Z;
  /// docs/theory.md §5.5, "Tolerance": below this max |a| is rounding, 4 ε max_i
  /// (‖(∂a_i/∂q_j q_j)_j‖₂ + ‖(∂a_i/∂v_j v_j)_j‖₂).
  double floor = 0.0;
};

Linearised linearised_at(const DynamicsJacobian& jac, Dynamics& dyn, double t,
                         const std::vector<double>& q, const std::vector<double>& v,
                         const Unknowns& unknowns, int it) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv), nu = static_cast<long>(unknowns.size()),
             np = static_cast<long>(unknowns.positions.size());
  StateJacobian J;
  try {
    J = jac.evaluate(dyn, t, q.data(), v.data());
  } catch (const NotDifferentiable& e) {
    throw NotDifferentiable(
        fmt::format("trim: at iteration {}, {}; stopped at {}", it, e.what(), describe(cm, q, v)));
  }
  const TangentChart chart = tangent_chart(cm, q.data(), v.data());
  const Eigen::SparseMatrix<double> T = chart.T.sparseView();
  const Eigen::MatrixXd Ax = J.a_q * T;
  Linearised L;
  L.floor = 4 * (rounding_level(J.a_q, Eigen::Map<const Eigen::VectorXd>(q.data(), J.a_q.cols())) +
                 rounding_level(J.a_v, Eigen::Map<const Eigen::VectorXd>(v.data(), J.a_v.cols())));
  // docs/theory.md §5.5, "Tolerance": the floor may lift the tolerance to kFloorCap of the
  // accelerations' change per unit coordinate, ε|x| ≈ 10⁻⁶; beyond, x is too far out for its
  // rounding to leave any acceleration meaningful, and no state there is called an equilibrium.
  const double scale = (rounding_level(J.a_q, Eigen::VectorXd::Ones(J.a_q.cols())) +
                        rounding_level(J.a_v, Eigen::VectorXd::Ones(J.a_v.cols()))) /
                       std::numeric_limits<double>::epsilon();
  if (L.floor > kFloorCap * scale)
    throw AnalysisError(fmt::format(
        "trim: the state is too far out for double precision: at {} the rounding of the "
        "coordinates alone moves the accelerations by {:.3g}, more than {:g} of their change per "
        "unit coordinate ({:.3g}); no state there can be told to be an equilibrium",
        describe(cm, q, v), L.floor, kFloorCap, scale));
  L.Af.resize(n, nu);
  for (long k = 0; k < np; ++k) L.Af.col(k) = Ax.col(unknowns.positions[static_cast<size_t>(k)]);
  const long nr = np + static_cast<long>(unknowns.rates.size());
  for (long k = np; k < nr; ++k)
    L.Af.col(k) = J.a_v.col(unknowns.rates[static_cast<size_t>(k - np)]);
  for (long k = nr; k < nu; ++k)
    L.Af.col(k) = J.a_w.col(unknowns.inputs[static_cast<size_t>(k - nr)].column);
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
  const long nr = np + static_cast<long>(unknowns.rates.size());
  for (long k = np; k < nr; ++k)
    v[static_cast<size_t>(unknowns.rates[static_cast<size_t>(k - np)])] += step[k];
  std::vector<double> w = state.inputs;
  for (long k = nr; k < step.size(); ++k) w[static_cast<size_t>(k - nr)] += step[k];
  set_inputs(dyn, unknowns, w);
  Residual next;
  try {
    next = residual_at(dyn, t, q, v, held);
  } catch (const SimulationError&) {
    return false;  // a singular point on the way
  }
  if (!std::isfinite(next.norm) || !next.on_manifold) return false;
  state.q = std::move(q);
  state.v = std::move(v);
  state.inputs = std::move(w);
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
  double previous = -1.0, best = INFINITY, floor = 0.0;
  int since_best = 0;  // steps with a large Δτ since max |a| last halved
  for (int it = 0;; ++it) {
    result.iterations = it;
    result.residual = r.a.size() ? r.a.cwiseAbs().maxCoeff() : 0.0;
    result.tolerance = std::max(options.tol, floor);
    if (result.residual <= result.tolerance) return "";
    if (it == options.max_pseudo_steps)
      return fmt::format("{} steps, max |acceleration| = {:.3g}", it, result.residual);
    if (result.residual < 0.5 * best) {
      best = result.residual;
      since_best = 0;
    } else if (dtau > 1e4 * options.pseudo_step && ++since_best == 50) {
      // Only once the steps are nearly Newton's: before that ‖a‖ may rise for a while as the
      // slow modes start to move.
      return fmt::format("stalled: max |acceleration| has not halved in 50 steps, {:.3g} after {}",
                         result.residual, it);
    }
    const Linearised L = linearised_at(jac, dyn, t, result.q, result.v, unknowns, it);
    floor = L.floor;
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
      result = std::move(trial);
      r = std::move(next);
      accepted = true;
      dtau *= 10.0;
    }
    if (!accepted) return fmt::format("no step accepted at step {} down to Δτ = {:.3g}", it, dtau);
  }
}

// "the accelerations do not change along 'x'" for a Jacobian Jr = Af Z of rank below its
// columns: the coordinate that moves most along the first direction of its null space.
std::string flat_direction(const DynamicsJacobian& jac, const std::vector<double>& q,
                           const std::vector<double>& v, const Unknowns& unknowns,
                           const Eigen::MatrixXd& Z, const Eigen::MatrixXd& Jr) {
  const CompiledModel& cm = jac.model();
  const Eigen::MatrixXd N = Eigen::FullPivLU<Eigen::MatrixXd>(Jr).setThreshold(1e-10).kernel();
  if (N.cols() == 0 || N.col(0).norm() == 0) return "";
  Eigen::Index top = 0;
  (Z * N.col(0)).cwiseAbs().maxCoeff(&top);
  const long np = static_cast<long>(unknowns.positions.size()),
             nr = np + static_cast<long>(unknowns.rates.size());
  std::string name;
  if (top < np)
    name = tangent_chart(cm, q.data(), v.data())
               .names[static_cast<size_t>(unknowns.positions[static_cast<size_t>(top)])];
  else if (top < nr)
    name = cm.velocity_names[static_cast<size_t>(unknowns.rates[static_cast<size_t>(top - np)])];
  else
    name = jac.input_names()[static_cast<size_t>(
        unknowns.inputs[static_cast<size_t>(top - nr)].column)];
  return fmt::format("the accelerations do not change along '{}'", name);
}

// docs/theory.md §5.5, "Levenberg–Marquardt": minimise f = ½‖W a‖², W = diag(M)^½ at the start,
// over the unknowns along the manifold (δ = Z ξ, J = W (∂a/∂u) Z). Each iteration first tries
// the Gauss–Newton step J ξ = −W a (column-pivoted QR, least squares) when J has full rank and
// takes it when ‖W a‖ falls by the Armijo fraction 1e-4; otherwise damped steps
// (Jᵀ J + μ D) ξ = −Jᵀ W a, μ updated by the gain ratio ρ = (f − f_new)/(½ ξᵀ(μ D ξ − Jᵀ W a))
// (Nielsen 1999): accepted when ρ > 1e-4, then μ ← μ max(1/10, 1 − (2ρ − 1)³); refused,
// μ ← μ ν, ν ← 2ν. Every accepted step decreases f. Returns why it stopped, or "" on
// convergence (with result.tolerance and, where J is singular there, result.not_isolated).
std::string levenberg_marquardt(const DynamicsJacobian& jac, Dynamics& dyn, double t,
                                const Unknowns& unknowns, const std::vector<bool>& held,
                                const TrimOptions& options, const char* what, TrimResult& result,
                                Residual& r) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv);
  // The mass-weighted residual W a, W = diag(M)^½ at the start: generalised forces over √mass,
  // so a light distal link's acceleration does not outweigh the arm's.
  Eigen::VectorXd w = Eigen::VectorXd::Ones(n);
  {
    const ImplicitJacobian I = jac.implicit(dyn, t, result.q.data(), result.v.data());
    for (long i = 0; i < n; ++i)
      if (I.K.coeff(i, i) > 0.0) w[i] = std::sqrt(I.K.coeff(i, i));
  }
  double mu = 0.0, nu = 2.0;
  for (int it = 0;; ++it) {
    result.iterations = it;
    result.residual = n ? r.a.cwiseAbs().maxCoeff() : 0.0;
    set_inputs(dyn, unknowns, result.inputs);  // a refused trial may have left others
    const Linearised L = linearised_at(jac, dyn, t, result.q, result.v, unknowns, it);
    result.tolerance = std::max(options.tol, L.floor);
    const Eigen::MatrixXd Jr = L.Af * L.Z;
    if (result.residual <= result.tolerance) {
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Jr);
      qr.setThreshold(1e-10);
      if (qr.rank() < Jr.cols())
        result.not_isolated = fmt::format(
            "not isolated: the Jacobian has rank {} of {} here ({}), one of a family of {}",
            qr.rank(), Jr.cols(), flat_direction(jac, result.q, result.v, unknowns, L.Z, Jr),
            std::string(what) == "equilibrium" ? "equilibria" : "steady states");
      return "";
    }
    if (it == options.max_iterations)
      return fmt::format("trim did not converge in {} iterations: max |acceleration| = {:.3g}", it,
                         result.residual);
    const Eigen::MatrixXd Jw = w.asDiagonal() * Jr;
    const Eigen::VectorXd rw = w.cwiseProduct(r.a);
    const Eigen::VectorXd g = Jw.transpose() * rw;
    // The step's metric D = Zᵀ diag(d) Z over the unknowns: positions mass-weighted (d = W²),
    // rates as they are, an input like the stiffest of those (Marquardt's diag(Jᵀ J) when only
    // inputs vary).
    const long nk = static_cast<long>(unknowns.size()),
               np = static_cast<long>(unknowns.positions.size()),
               nr = np + static_cast<long>(unknowns.rates.size());
    Eigen::VectorXd d = Eigen::VectorXd::Ones(nk);
    for (long k = 0; k < np; ++k) d[k] = std::pow(w[unknowns.positions[static_cast<size_t>(k)]], 2);
    const Eigen::VectorXd column2 = (w.asDiagonal() * L.Af).colwise().squaredNorm().transpose();
    double stiffest = 0.0;
    for (long k = 0; k < nr; ++k) stiffest = std::max(stiffest, column2[k] / d[k]);
    for (long k = nr; k < nk; ++k)
      if (column2[k] > 0.0) d[k] = column2[k] / (stiffest > 0.0 ? stiffest : 1.0);
    const Eigen::MatrixXd Dm = L.Z.transpose() * d.asDiagonal() * L.Z;
    const double f = 0.5 * rw.squaredNorm();
    bool accepted = false;
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Jw);
    qr.setThreshold(1e-10);
    if (qr.rank() == Jw.cols()) {
      const Eigen::VectorXd xi = qr.solve(Eigen::VectorXd(-rw));
      TrimResult trial = result;
      Residual next;
      if (xi.allFinite() && try_step(dyn, t, unknowns, L.Z * xi, held, trial, next) &&
          w.cwiseProduct(next.a).norm() <= (1.0 - 1e-4) * rw.norm()) {
        result = std::move(trial);
        r = std::move(next);
        accepted = true;
      }
    }
    if (!accepted) {
      Eigen::MatrixXd H = Jw.transpose() * Jw;
      const double scale = H.rows() ? H.diagonal().cwiseQuotient(Dm.diagonal()).maxCoeff() : 0.0;
      if (mu <= 0.0) mu = 1e-3 * scale;
      for (int k = 0; k < 60 && !accepted && g.norm() > 0.0 && mu > 0.0; ++k) {
        const Eigen::MatrixXd A = H + mu * Dm;
        const Eigen::VectorXd xi = A.ldlt().solve(-g);
        const double predicted = 0.5 * xi.dot(mu * Dm * xi - g);
        TrimResult trial = result;
        Residual next;
        if (xi.allFinite() && predicted > 0.0 &&
            try_step(dyn, t, unknowns, L.Z * xi, held, trial, next)) {
          const double rho = (f - 0.5 * w.cwiseProduct(next.a).squaredNorm()) / predicted;
          if (rho > 1e-4) {
            result = std::move(trial);
            r = std::move(next);
            accepted = true;
            mu *= std::max(0.1, 1.0 - std::pow(2.0 * rho - 1.0, 3));
            nu = 2.0;
            continue;
          }
        }
        mu *= nu;
        nu *= 2.0;
      }
    }
    if (!accepted) {
      // f is stationary to within what the steps resolve: ‖a‖ has a local minimum that is
      // not zero. Where the Jacobian is singular, say along what.
      std::string why = fmt::format(
          "trim: no equilibrium near the start: no step reduces the accelerations at iteration "
          "{}, where |a| has a local minimum that is not {} (gradient |Jᵀa| = {:.3g})",
          it, std::string(what) == "equilibrium" ? "an equilibrium" : "a steady state", g.norm());
      if (qr.rank() < Jr.cols())
        why += fmt::format("; the Jacobian ∂a/∂q is singular there (rank {} of {}, {})", qr.rank(),
                           Jr.cols(), flat_direction(jac, result.q, result.v, unknowns, L.Z, Jr));
      if (unknowns.size() < static_cast<size_t>(n))
        why += "; or there is none with these coordinates free";
      return why;
    }
  }
}

}  // namespace

TrimResult trim(const DynamicsJacobian& jac, Dynamics& dyn, double t, const std::vector<double>& q0,
                const TrimOptions& options) {
  return trim(jac, dyn, t, q0, std::vector<double>(jac.model().nv, 0.0), options);
}

// docs/theory.md §5.5: solve a(x, v) = 0 for the unknowns u (free tangent coordinates x and
// free held rates) by Levenberg–Marquardt steps along the constraint manifold; when that stops
// short, pseudo-transient continuation from the start.
TrimResult trim(const DynamicsJacobian& jac, Dynamics& dyn, double t, const std::vector<double>& q0,
                const std::vector<double>& v0, const TrimOptions& options) {
  const CompiledModel& cm = jac.model();
  const long n = static_cast<long>(cm.nv);
  if (v0.size() != cm.nv)
    throw std::invalid_argument(fmt::format("expected {} velocities, got {}", cm.nv, v0.size()));
  std::vector<bool> steady;
  const Unknowns unknowns = unknowns_of(jac, options, steady);
  std::vector<bool> held(cm.nq, false);
  for (size_t i = 0; i < cm.plain; ++i)
    held[i] = std::find(unknowns.positions.begin(), unknowns.positions.end(),
                        static_cast<long>(i)) == unknowns.positions.end();
  const bool held_rates = std::find(steady.begin(), steady.end(), true) != steady.end();
  const char* what = held_rates ? "steady state" : "equilibrium";
  if (!(options.tol > 0 && std::isfinite(options.tol)))
    throw std::invalid_argument(
        fmt::format("trim: the tolerance must be positive and finite, got {}", options.tol));

  TrimResult start;
  start.q = q0;
  start.v.assign(cm.nv, 0.0);
  for (size_t i = 0; i < cm.nv; ++i)
    if (steady[i]) start.v[i] = v0[i];
  start.inputs = input_values(dyn, unknowns, t, start.q, start.v);
  const Residual r0 = residual_at(dyn, t, start.q, start.v, held);
  TrimResult result = start;
  Residual r = r0;
  std::string failed;
  try {
    failed = levenberg_marquardt(jac, dyn, t, unknowns, held, options, what, result, r);
  } catch (const AnalysisError&) {
    set_inputs(dyn, unknowns, start.inputs);  // on failure the start values are restored
    throw;
  }
  if (!failed.empty()) {
    const std::string where =
        fmt::format("{}; stopped at {} with max |acceleration| = {:.3g}", failed,
                    describe(cm, result.q, result.v), result.residual);
    set_inputs(dyn, unknowns, start.inputs);
    if (!unknowns.rates.empty() || !unknowns.inputs.empty() || options.max_pseudo_steps <= 0)
      throw AnalysisError(where);
    TrimResult relaxed = start;
    Residual rr = r0;
    std::string why;
    try {
      why = pseudo_transient(jac, dyn, t, unknowns, held, options, relaxed, rr);
    } catch (const AnalysisError&) {
      set_inputs(dyn, unknowns, start.inputs);
      throw;
    }
    if (!why.empty())
      throw AnalysisError(fmt::format(
          "{}; pseudo-transient continuation from the start failed too ({}), stopped at {}", where,
          why, describe(cm, relaxed.q, relaxed.v)));
    result = std::move(relaxed);
    result.pseudo_transient = true;
  }
  set_inputs(dyn, unknowns, result.inputs);
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
