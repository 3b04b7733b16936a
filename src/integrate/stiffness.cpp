// The stiffness estimate behind `--integrator auto` (include/lagrange/integrator.hpp).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lagrange/integrator.hpp"

namespace lagrange {

namespace {

/// x ← J x for the compressed-column J.
void multiply(const OdeJacobian& jac, const std::vector<double>& values,
              const std::vector<double>& x, std::vector<double>& out) {
  std::fill(out.begin(), out.end(), 0.0);
  for (size_t j = 0; j + 1 < jac.column_starts.size(); ++j)
    for (long e = jac.column_starts[j]; e < jac.column_starts[j + 1]; ++e)
      out[static_cast<size_t>(jac.rows[static_cast<size_t>(e)])] +=
          values[static_cast<size_t>(e)] * x[j];
}

double norm(const std::vector<double>& x) {
  double s = 0.0;
  for (double v : x) s += v * v;
  return std::sqrt(s);
}

}  // namespace

// docs/theory.md §5.6, "Choosing the method".
double spectral_radius_estimate(const OdeJacobian& jac, double t, const std::vector<double>& y) {
  if (!jac.values || jac.column_starts.size() != y.size() + 1)
    throw std::invalid_argument(
        fmt::format("spectral_radius_estimate: expected a Jacobian of {} columns", y.size()));
  std::vector<double> values(jac.nonzeros());
  jac.values(t, y.data(), values.data());
  std::vector<double> x(y.size()), next(y.size());
  for (size_t i = 0; i < x.size(); ++i) x[i] = 1.0 + 0.1 * std::sin(1.0 + static_cast<double>(i));
  double scale = norm(x);
  for (double& v : x) v /= scale;
  // ‖Jᵏx‖^(1/k) → ρ(J) for a generic x, complex pairs included (power iteration on growth).
  constexpr int kIterations = 60;
  double log_growth = 0.0;
  for (int k = 0; k < kIterations; ++k) {
    multiply(jac, values, x, next);
    scale = norm(next);
    if (!(scale > 0.0) || !std::isfinite(scale)) return scale > 0.0 ? scale : 0.0;
    log_growth += std::log(scale);
    for (size_t i = 0; i < x.size(); ++i) x[i] = next[i] / scale;
  }
  return std::exp(log_growth / kIterations);
}

std::string choose_ode_method(const OdeJacobian& jac, double t, const std::vector<double>& y,
                              double output_step) {
  if (!jac.values) return "dop853";
  const double rho = spectral_radius_estimate(jac, t, y);
  return rho * output_step > kStiffnessThreshold ? "cvode:jacobian" : "dop853";
}

}  // namespace lagrange
