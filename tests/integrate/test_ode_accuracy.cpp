// Accuracy against closed-form solutions: harmonic oscillator (ARKODE, CVODE), RK4 convergence
// order, and a stiff linear problem for CVODE.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "integrate/oscillator.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

using test::options_for;
using test::Oscillator;

/// Largest |x − x_exact| over the output grid of the oscillator from (1, 0) on [0, t_end].
double oscillator_error(const IntegratorOptions& options, double t_end, double dt,
                        std::vector<double>* times = nullptr, IntegratorStats* stats = nullptr) {
  const Oscillator osc;
  double worst = 0.0;
  const IntegratorStats s = integrate(
      osc.problem(), options, 0.0, {1.0, 0.0}, t_end, dt, [&](double t, double* y, double*) {
        if (times) times->push_back(t);
        worst = std::max({worst, std::abs(y[0] - osc.x(t, 0.0, 1.0, 0.0)),
                          std::abs(y[1] - osc.v(t, 0.0, 1.0, 0.0))});
        return ObserverAction::Continue;
      });
  if (stats) *stats = s;
  return worst;
}

class AdaptiveOscillator : public ::testing::TestWithParam<const char*> {};

TEST_P(AdaptiveOscillator, MatchesClosedFormOnTheExactGrid) {
  std::vector<double> times;
  IntegratorStats stats;
  const double error =
      oscillator_error(options_for(GetParam(), 1e-12, 1e-14), 10.0, 0.1, &times, &stats);
  EXPECT_LT(error, 1e-8);
  ASSERT_EQ(times.size(), 101u);
  for (size_t k = 0; k + 1 < times.size(); ++k) EXPECT_EQ(times[k], static_cast<double>(k) * 0.1);
  EXPECT_EQ(times.back(), 10.0);
  EXPECT_GT(stats.steps, 0);
  EXPECT_GE(stats.rhs_evals, stats.steps);
  EXPECT_GE(stats.failed_steps, 0);
}

TEST_P(AdaptiveOscillator, LandsOnAShortLastInterval) {
  std::vector<double> times;
  const double error = oscillator_error(options_for(GetParam(), 1e-10, 1e-12), 1.0, 0.3, &times);
  EXPECT_LT(error, 1e-7);
  EXPECT_EQ(times, (std::vector<double>{0.0, 0.3, 2 * 0.3, 3 * 0.3, 1.0}));
}

INSTANTIATE_TEST_SUITE_P(Methods, AdaptiveOscillator, ::testing::Values("arkode", "cvode"));

TEST(Rk4, ErrorShrinksSixteenfoldWhenTheStepHalves) {
  IntegratorOptions coarse = options_for("rk4");
  coarse.step = 0.05;
  IntegratorOptions fine = coarse;
  fine.step = 0.025;
  IntegratorStats coarse_stats;
  const double e_coarse = oscillator_error(coarse, 4.0, 0.5, nullptr, &coarse_stats);
  const double e_fine = oscillator_error(fine, 4.0, 0.5);
  const double ratio = e_coarse / e_fine;
  EXPECT_GT(ratio, 12.0) << "coarse " << e_coarse << " fine " << e_fine;
  EXPECT_LT(ratio, 20.0) << "coarse " << e_coarse << " fine " << e_fine;
  EXPECT_EQ(coarse_stats.steps, 80);  // 8 intervals of 10 steps
  EXPECT_EQ(coarse_stats.rhs_evals, 4 * 80);
  EXPECT_EQ(coarse_stats.failed_steps, 0);
}

TEST(Rk4, DefaultStepIsATenthOfTheOutputStepAndFitsEachInterval) {
  IntegratorStats stats;
  oscillator_error(options_for("rk4"), 1.0, 0.3, nullptr, &stats);
  EXPECT_EQ(stats.steps, 3 * 10 + 4);  // the last interval (0.1) gets ceil(0.1 / 0.03) = 4 steps
}

// y' = −λ (y − cos t), y(0) = 0, λ = 1000:
// y = A cos t + B sin t − A e^{−λt}, A = λ²/(1 + λ²), B = λ/(1 + λ²) (variation of constants).
TEST(Cvode, SolvesAStiffProblemInFewSteps) {
  const double lambda = 1000.0;
  const OdeProblem stiff{1,
                         [lambda](double t, const double* y, double* ydot) {
                           ydot[0] = -lambda * (y[0] - std::cos(t));
                         },
                         {}};
  const double a = lambda * lambda / (1.0 + lambda * lambda);
  const double b = lambda / (1.0 + lambda * lambda);
  const auto exact = [&](double t) {
    return a * std::cos(t) + b * std::sin(t) - a * std::exp(-lambda * t);
  };
  const auto run = [&](const char* method, double* worst) {
    return integrate(stiff, options_for(method, 1e-8, 1e-10), 0.0, {0.0}, 10.0, 0.5,
                     [&](double t, double* y, double*) {
                       *worst = std::max(*worst, std::abs(y[0] - exact(t)));
                       return ObserverAction::Continue;
                     });
  };
  double bdf_error = 0.0, erk_error = 0.0;
  const IntegratorStats bdf = run("cvode", &bdf_error);
  const IntegratorStats erk = run("arkode", &erk_error);
  EXPECT_LT(bdf_error, 1e-6);
  EXPECT_LT(erk_error, 1e-6);
  // Explicit RK is held to h ≲ 3/λ by stability (≳ 3000 steps on [0, 10]); BDF is not.
  EXPECT_LT(bdf.steps, 600) << "cvode steps " << bdf.steps;
  EXPECT_GT(erk.steps, 5 * bdf.steps) << "arkode " << erk.steps << " cvode " << bdf.steps;
}

}  // namespace
}  // namespace lagrange
