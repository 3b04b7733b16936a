// The exact Jacobian of the first-order form y' = f(y), y = (q, v), for implicit integrators
// (include/lagrange/analysis.hpp, ode_jacobian).

#include <fmt/format.h>

#include <random>
#include <stdexcept>

#include "lagrange/analysis.hpp"

namespace lagrange {

namespace {

/// The pattern's rows of the acceleration block per column of y: the entries of [a_q a_v] that
/// are non-zero at `states` (structural non-zeros are non-zero at a generic state).
std::vector<std::vector<bool>> probe(const DynamicsJacobian& jac, Dynamics& dyn, double t,
                                     const std::vector<std::vector<double>>& states) {
  const CompiledModel& cm = jac.model();
  const size_t nq = cm.nq, nv = cm.nv;
  std::vector<std::vector<bool>> used(nq + nv, std::vector<bool>(nv, false));
  for (const auto& y : states) {
    const StateJacobian J = jac.evaluate(dyn, t, y.data(), y.data() + nq);
    for (size_t j = 0; j < nq + nv; ++j)
      for (size_t i = 0; i < nv; ++i) {
        const long r = static_cast<long>(i);
        const double d =
            j < nq ? J.a_q(r, static_cast<long>(j)) : J.a_v(r, static_cast<long>(j - nq));
        if (d != 0.0) used[j][i] = true;
      }
  }
  return used;
}

}  // namespace

// docs/theory.md §5.6, "The Jacobian of the first-order form".
OdeJacobian ode_jacobian(const DynamicsJacobian& jac, Dynamics& dyn, double t0,
                         const std::vector<double>& y0) {
  const CompiledModel& cm = jac.model();
  const size_t nq = cm.nq, nv = cm.nv, n = nq + nv;
  if (cm.plain != nq || nq != nv)
    throw std::invalid_argument(fmt::format(
        "the exact ODE Jacobian needs plain coordinates only (q̇ = v); this model has {} free "
        "bod{} (use cvode or dop853)",
        cm.rotations.size(), cm.rotations.size() == 1 ? "y" : "ies"));
  if (y0.size() != n)
    throw std::invalid_argument(
        fmt::format("ode_jacobian: expected a state of {} values, got {}", n, y0.size()));
  // The state itself and two states nearby (relative and absolute changes of 1e-3, fixed seed).
  std::vector<std::vector<double>> states{y0};
  std::mt19937 random(22);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 2; ++k) {
    std::vector<double> y = y0;
    for (double& x : y) x += 1e-3 * (unit(random) * x + unit(random));
    states.push_back(std::move(y));
  }
  const std::vector<std::vector<bool>> used = probe(jac, dyn, t0, states);

  OdeJacobian out;
  out.column_starts.push_back(0);
  for (size_t j = 0; j < n; ++j) {
    // rows: q̇_j = v_j gives (j − nq, j) for a velocity column; the diagonal is kept for the
    // Newton matrix I − γJ; then the accelerations.
    if (j < nq) out.rows.push_back(static_cast<long>(j));
    if (j >= nq) out.rows.push_back(static_cast<long>(j - nq));
    for (size_t i = 0; i < nv; ++i)
      if (used[j][i] || nq + i == j) out.rows.push_back(static_cast<long>(nq + i));
    out.column_starts.push_back(static_cast<long>(out.rows.size()));
  }
  const OdeJacobian pattern = out;  // the values callback reads the pattern from its own copy
  out.values = [&jac, &dyn, pattern, nq](double t, const double* y, double* values) {
    const StateJacobian J = jac.evaluate(dyn, t, y, y + nq);
    const size_t n = 2 * nq;
    for (size_t j = 0; j < n; ++j)
      for (long e = pattern.column_starts[j]; e < pattern.column_starts[j + 1]; ++e) {
        const size_t r = static_cast<size_t>(pattern.rows[static_cast<size_t>(e)]);
        double d = 0.0;
        if (r < nq)
          d = j == nq + r ? 1.0 : 0.0;
        else if (j < nq)
          d = J.a_q(static_cast<long>(r - nq), static_cast<long>(j));
        else
          d = J.a_v(static_cast<long>(r - nq), static_cast<long>(j - nq));
        values[e] = d;
      }
  };
  return out;
}

}  // namespace lagrange
