// The exact Jacobian of the first-order form y' = f(y), y = (q, v), for implicit integrators
// (include/lagrange/analysis.hpp, ode_jacobian).

#include <fmt/format.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "analysis/off_kink.hpp"
#include "lagrange/analysis.hpp"

namespace lagrange {

namespace {

/// ∂f_r/∂y_j from one evaluation: rows 0..nq of f are q̇, then the accelerations.
double entry(const StateJacobian& J, size_t nq, size_t r, size_t j) {
  const long row = static_cast<long>(r < nq ? r : r - nq);
  const long col = static_cast<long>(j < nq ? j : j - nq);
  if (r < nq) return j < nq ? J.qdot_q(row, col) : J.qdot_v(row, col);
  return j < nq ? J.a_q(row, col) : J.a_v(row, col);
}

/// The derivatives at (t, y), with the limits of removable 0/0s (docs/theory.md §5.1); at a kink
/// of max/min (|x| at x = 0, e.g. a slack tether segment at rest), where they do not exist,
/// one-sided ones: those at a state moved by 1e-9 relative (docs/theory.md §5.6).
StateJacobian evaluate(const DynamicsJacobian& jac, Dynamics& dyn, double t, const double* y) {
  const size_t nq = jac.model().nq, n = nq + jac.model().nv;
  std::mt19937 random(5);
  for (int attempt = 0;; ++attempt) {
    try {
      if (attempt == 0) return jac.evaluate(dyn, t, y, y + nq);
      const std::vector<double> moved = analysis_detail::off_kink(y, n, random);
      return jac.evaluate(dyn, t, moved.data(), moved.data() + nq);
    } catch (const NotDifferentiable&) {
      if (attempt == 3) throw;
    }
  }
}

/// Per column of y, the rows of f whose derivative is non-zero at some of `states`
/// (structural non-zeros are non-zero at a generic state).
std::vector<std::vector<bool>> probe(const DynamicsJacobian& jac, Dynamics& dyn, double t,
                                     const std::vector<std::vector<double>>& states) {
  const CompiledModel& cm = jac.model();
  const size_t nq = cm.nq, n = cm.nq + cm.nv;
  std::vector<std::vector<bool>> used(n, std::vector<bool>(n, false));
  for (const auto& y : states) {
    const StateJacobian J = evaluate(jac, dyn, t, y.data());
    for (size_t j = 0; j < n; ++j)
      for (size_t r = 0; r < n; ++r)
        if (entry(J, nq, r, j) != 0.0) used[j][r] = true;
  }
  return used;
}

}  // namespace

// docs/theory.md §5.6, "The Jacobian of the first-order form".
OdeJacobian ode_jacobian(const DynamicsJacobian& jac, Dynamics& dyn, double t0,
                         const std::vector<double>& y0) {
  const CompiledModel& cm = jac.model();
  const size_t nq = cm.nq, n = nq + cm.nv;
  if (y0.size() != n)
    throw std::invalid_argument(
        fmt::format("ode_jacobian: expected a state of {} values, got {}", n, y0.size()));
  // The state itself and two states nearby (relative and absolute changes of 1e-3, fixed seed):
  // R then leaves SO(3) a little, where the drift correction's derivatives are generic too.
  std::vector<std::vector<double>> states{y0};
  std::mt19937 random(22);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int k = 0; k < 2; ++k) {
    std::vector<double> y = y0;
    for (double& x : y) x += 1e-3 * (unit(random) * x + unit(random));
    states.push_back(std::move(y));
  }
  const std::vector<std::vector<bool>> used = probe(jac, dyn, t0, states);

  // The diagonal is kept for the Newton matrix I − γJ.
  OdeJacobian out;
  out.column_starts.push_back(0);
  for (size_t j = 0; j < n; ++j) {
    for (size_t r = 0; r < n; ++r)
      if (used[j][r] || r == j) out.rows.push_back(static_cast<long>(r));
    out.column_starts.push_back(static_cast<long>(out.rows.size()));
  }
  const OdeJacobian pattern = out;  // the values callback reads the pattern from its own copy
  out.values = [&jac, &dyn, pattern, nq, n](double t, const double* y, double* values) {
    const StateJacobian J = evaluate(jac, dyn, t, y);
    for (size_t j = 0; j < n; ++j)
      for (long e = pattern.column_starts[j]; e < pattern.column_starts[j + 1]; ++e)
        values[e] = entry(J, nq, static_cast<size_t>(pattern.rows[static_cast<size_t>(e)]), j);
  };
  return out;
}

}  // namespace lagrange
