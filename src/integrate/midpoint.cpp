#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "integrate/fixed_steps.hpp"
#include "integrate/keeping_stats.hpp"
#include "integrate/methods.hpp"
#include "integrate/solver_errors.hpp"
#include "lagrange/error.hpp"

namespace lagrange::integration {

namespace {

constexpr int kMaxIterations = 100;

double max_abs(const std::vector<double>& x) {
  double r = 0.0;
  for (double v : x) r = std::max(r, std::abs(v));
  return r;
}

}  // namespace

// docs/theory.md §8: the midpoint z = (y₀ + y₁)/2 solves z = y₀ + (h/2) f(t + h/2, z). Fixed-point
// iteration from the extrapolation z = y₀ + (h/2)(y₀ − y₋₁)/h contracts by about hL/2 per sweep;
// it stops when a sweep changes z by no more than rounding (or stops shrinking the change once
// it is within 1e-12 of |z|), so that the map stays symmetric to rounding level — the property
// that keeps the energy error from drifting.
IntegratorStats integrate_midpoint(const OdeProblem& problem, const IntegratorOptions& options,
                                   const OutputGrid& grid, std::vector<double>& y,
                                   const Observer& observer) {
  const size_t n = y.size();
  std::vector<double> slope(n, 0.0), z(n), f(n);
  IntegratorStats stats;
  const auto step = [&](double t, double h) {
    for (size_t i = 0; i < n; ++i) z[i] = y[i] + 0.5 * h * slope[i];
    double previous = HUGE_VAL, worst = 0.0;  // the largest factor a sweep scaled the change by
    for (int iteration = 0;; ++iteration) {
      problem.rhs(t + 0.5 * h, z.data(), f.data());
      ensure_finite(t + 0.5 * h, f.data(), n, "right-hand side ydot");
      ++stats.rhs_evals;
      double change = 0.0;
      for (size_t i = 0; i < n; ++i) {
        const double next = y[i] + 0.5 * h * f[i];
        change = std::max(change, std::abs(next - z[i]));
        z[i] = next;
      }
      const double scale = 1.0 + max_abs(z);
      if (change <= 4e-16 * scale || (change >= previous && change <= 1e-12 * scale)) break;
      if (iteration == kMaxIterations || !(change < 1e300)) {
        // A sweep scales the change by about ρ = (h/2)·(the system's largest rate), more where
        // a force switches on (a one-sided spring going taut): ρ ≈ 0.3 converges in some 30
        // sweeps.
        const double ratio = std::max(worst, change / previous);
        const std::string rate =
            std::isfinite(ratio) && ratio > 0
                ? fmt::format(", sweeps scaling it by factors up to {:.3g}", ratio)
                : "";
        const std::string lower =
            std::isfinite(ratio) && ratio > 0
                ? fmt::format(" to about {:.2g}", h * 0.3 / std::max(ratio, 0.3))
                : "";
        throw SimulationError(
            t, fmt::format("implicit midpoint: the fixed-point iteration did not converge in {} "
                           "sweeps (last change {:.3g}{}); the step h = {:g} is too large for "
                           "this system: lower --step{}, or for a stiff model take an "
                           "integrator that solves its implicit equations by Newton's method "
                           "(--integrator cvode or ida)",
                           kMaxIterations, change, rate, h, lower));
      }
      if (std::isfinite(previous)) worst = std::max(worst, change / previous);
      previous = change;
    }
    for (size_t i = 0; i < n; ++i) {
      const double next = 2.0 * z[i] - y[i];
      slope[i] = (next - y[i]) / h;
      y[i] = next;
    }
    ++stats.steps;
  };
  keeping_stats([&] { walk_fixed_steps(grid, options, observer, y, step); }, [&] { return stats; });
  return stats;
}

}  // namespace lagrange::integration
