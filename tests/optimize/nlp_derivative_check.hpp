#pragma once
// Test helper: the NLP's exact derivatives (docs/theory.md §10) against central differences at a
// random point near the starting one, every entry (an entry missing from a pattern shows).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "optimize/transcription.hpp"

namespace lagrange::testing {

/// The starting point moved by up to ±0.3 in each variable (seeded), T = 1.3 when free.
inline std::vector<double> perturbed_guess(const collocation::Transcription& nlp, bool free_horizon,
                                           unsigned seed) {
  std::vector<double> x = nlp.guess();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> perturb(-0.3, 0.3);
  for (double& xi : x) xi += perturb(rng);
  if (free_horizon) x[0] = 1.3;
  return x;
}

/// Constraint Jacobian and objective gradient at x against central differences.
inline void expect_first_derivatives_match(collocation::Transcription& nlp, std::vector<double> x) {
  const size_t n = nlp.variables(), m = nlp.constraints();
  std::vector<double> J(nlp.jacobian_pattern().size()), grad(n);
  nlp.jacobian(x.data(), J.data());
  nlp.gradient(x.data(), grad.data());
  std::vector<std::vector<double>> dense(m, std::vector<double>(n, 0.0));
  for (size_t e = 0; e < J.size(); ++e)
    dense[nlp.jacobian_pattern()[e].first][nlp.jacobian_pattern()[e].second] = J[e];
  std::vector<double> gp(m), gm(m);
  for (size_t c = 0; c < n; ++c) {
    const double step = 1e-6 * std::max(1.0, std::fabs(x[c])), keep = x[c];
    x[c] = keep + step;
    nlp.constraint_values(x.data(), gp.data());
    const double fp = nlp.objective(x.data());
    x[c] = keep - step;
    nlp.constraint_values(x.data(), gm.data());
    const double fm = nlp.objective(x.data());
    x[c] = keep;
    for (size_t r = 0; r < m; ++r) {
      const double fd = (gp[r] - gm[r]) / (2 * step);
      ASSERT_NEAR(dense[r][c], fd, 1e-5 * std::max(1.0, std::fabs(fd)))
          << nlp.describe(r, x.data()) << ", variable " << c;
    }
    const double fd = (fp - fm) / (2 * step);
    ASSERT_NEAR(grad[c], fd, 1e-5 * std::max(1.0, std::fabs(fd))) << "gradient, variable " << c;
  }
}

/// The Hessian of the Lagrangian σ∇²J + Σ y_r ∇²g_r at x against central differences of its
/// gradient σ∇J + Jᵀy (both checked by expect_first_derivatives_match), with random multipliers
/// (seeded), every entry.
inline void expect_hessian_matches(collocation::Transcription& nlp, std::vector<double> x,
                                   unsigned seed) {
  ASSERT_TRUE(nlp.has_hessian());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> multiplier(-2.0, 2.0);
  const size_t n = nlp.variables(), m = nlp.constraints();
  std::vector<double> y(m);
  for (double& yi : y) yi = multiplier(rng);
  const double sigma = 0.7;
  std::vector<double> J(nlp.jacobian_pattern().size()), grad(n);
  const auto lagrangian_gradient = [&](std::vector<double>& out) {
    nlp.gradient(x.data(), grad.data());
    nlp.jacobian(x.data(), J.data());
    for (size_t i = 0; i < n; ++i) out[i] = sigma * grad[i];
    for (size_t e = 0; e < J.size(); ++e) {
      const auto [r, c] = nlp.jacobian_pattern()[e];
      out[c] += y[r] * J[e];
    }
  };
  std::vector<double> H(nlp.hessian_pattern().size());
  nlp.hessian(x.data(), sigma, y.data(), H.data());
  std::vector<std::vector<double>> dense(n, std::vector<double>(n, 0.0));
  for (size_t e = 0; e < H.size(); ++e) {
    const auto [r, c] = nlp.hessian_pattern()[e];
    ASSERT_GE(r, c);
    dense[r][c] = dense[c][r] = H[e];
  }
  std::vector<double> lp(n), lm(n);
  for (size_t c = 0; c < n; ++c) {
    const double step = 1e-6 * std::max(1.0, std::fabs(x[c])), keep = x[c];
    x[c] = keep + step;
    lagrangian_gradient(lp);
    x[c] = keep - step;
    lagrangian_gradient(lm);
    x[c] = keep;
    for (size_t r = 0; r < n; ++r) {
      const double fd = (lp[r] - lm[r]) / (2 * step);
      ASSERT_NEAR(dense[r][c], fd, 2e-5 * std::max(1.0, std::fabs(fd)))
          << "entry (" << r << ", " << c << ")";
    }
  }
}

}  // namespace lagrange::testing
