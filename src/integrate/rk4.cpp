#include "integrate/fixed_steps.hpp"
#include "integrate/keeping_stats.hpp"
#include "integrate/methods.hpp"
#include "integrate/solver_errors.hpp"

namespace lagrange::integration {

IntegratorStats integrate_rk4(const OdeProblem& problem, const IntegratorOptions& options,
                              const OutputGrid& grid, std::vector<double>& y,
                              const Observer& observer) {
  const size_t n = y.size();
  std::vector<double> k1(n), k2(n), k3(n), k4(n), stage(n);
  IntegratorStats stats;
  const auto f = [&](double t, const double* state, double* out) {
    problem.rhs(t, state, out);
    ensure_finite(t, out, n, "right-hand side ydot");
    ++stats.rhs_evals;
  };
  // One classical RK4 step: y += h/6 (k1 + 2 k2 + 2 k3 + k4), k1 = f(t, y),
  // k2 = f(t + h/2, y + h/2 k1), k3 = f(t + h/2, y + h/2 k2), k4 = f(t + h, y + h k3).
  const auto step = [&](double t, double h) {
    f(t, y.data(), k1.data());
    for (size_t i = 0; i < n; ++i) stage[i] = y[i] + 0.5 * h * k1[i];
    f(t + 0.5 * h, stage.data(), k2.data());
    for (size_t i = 0; i < n; ++i) stage[i] = y[i] + 0.5 * h * k2[i];
    f(t + 0.5 * h, stage.data(), k3.data());
    for (size_t i = 0; i < n; ++i) stage[i] = y[i] + h * k3[i];
    f(t + h, stage.data(), k4.data());
    for (size_t i = 0; i < n; ++i) y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    ++stats.steps;
  };
  keeping_stats([&] { walk_fixed_steps(grid, options, observer, y, step); }, [&] { return stats; });
  return stats;
}

}  // namespace lagrange::integration
