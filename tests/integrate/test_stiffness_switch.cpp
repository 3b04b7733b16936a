// `auto` noticing stiffness during the run (docs/theory.md §5.6, "Noticing stiffness during the
// run"): DOP853's stiffness test hands a problem that stiffens over to cvode:jacobian on the
// same output grid, and leaves a non-stiff one alone.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "integrate/oscillator.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

// y' = −k t² (y − sin t) + cos t, y(0) = 0: y = sin t for every k, and ∂f/∂y = −k t², so the
// problem is not stiff at t = 0 (ρ = 0) and becomes stiff as t grows.
OdeProblem stiffening(double k) {
  OdeProblem p;
  p.size = 1;
  p.rhs = [k](double t, const double* y, double* ydot) {
    ydot[0] = -k * t * t * (y[0] - std::sin(t)) + std::cos(t);
  };
  p.jacobian.column_starts = {0, 1};
  p.jacobian.rows = {0};
  p.jacobian.values = [k](double t, const double*, double* values) { values[0] = -k * t * t; };
  return p;
}

struct SampledRun {
  IntegratorStats stats;
  double worst = 0.0;  ///< largest |y − sin t| over the samples
  int samples = 0;
};

SampledRun run(const OdeProblem& problem, const std::string& method) {
  IntegratorOptions options;
  options.method = method;
  options.rtol = 1e-8;
  options.atol = 1e-10;
  SampledRun r;
  double t_last = -1.0;
  r.stats = integrate(problem, options, 0.0, {0.0}, 2.0, 0.1, [&](double t, double* y, double*) {
    EXPECT_GT(t, t_last);  // every sample once, in order, across the handover
    t_last = t;
    r.worst = std::max(r.worst, std::abs(y[0] - std::sin(t)));
    ++r.samples;
    return ObserverAction::Continue;
  });
  return r;
}

TEST(StiffnessSwitch, StiffeningProblemTurnsImplicit) {
  const OdeProblem problem = stiffening(1e5);
  const SampledRun automatic = run(problem, "auto");
  const std::string& method = automatic.stats.method;
  EXPECT_EQ(method.rfind("dop853, stiff at t = ", 0), 0u) << method;
  const size_t from = method.find(": cvode:jacobian from t = ");
  ASSERT_NE(from, std::string::npos) << method;
  // h·|λ| = h k t² reaches DOP853's boundary 6.1 early, and 15 steps held there conclude the
  // test within the first few samples.
  EXPECT_LT(std::stod(method.substr(from + 26)), 0.5) << method;
  EXPECT_EQ(automatic.samples, 21);
  EXPECT_LT(automatic.worst, 1e-6);
  // DOP853 throughout is held at h ≈ 6.1 / (k t²): far more right-hand sides for the same answer.
  const SampledRun explicit_only = run(problem, "dop853");
  EXPECT_LT(explicit_only.worst, 1e-6);
  EXPECT_GT(explicit_only.stats.rhs_evals, 100 * automatic.stats.rhs_evals);
}

// y' = −k w(t) (y − sin t) + cos t with the window w = exp(−((t − 1.5)/0.4)⁸): y = sin t again,
// stiff (ρ = k w) only for t in about [1, 2]. `auto` turns implicit as the window opens and,
// once h·ρ of the BDF step is far below DOP853's bound, explicit again (docs/theory.md §5.6,
// "Returning to DOP853").
OdeProblem stiff_window(double k) {
  const auto w = [](double t) { return std::exp(-std::pow((t - 1.5) / 0.4, 8)); };
  OdeProblem p;
  p.size = 1;
  p.rhs = [k, w](double t, const double* y, double* ydot) {
    ydot[0] = -k * w(t) * (y[0] - std::sin(t)) + std::cos(t);
  };
  p.jacobian.column_starts = {0, 1};
  p.jacobian.rows = {0};
  p.jacobian.values = [k, w](double t, const double*, double* values) { values[0] = -k * w(t); };
  return p;
}

SampledRun run_window(const OdeProblem& problem, const std::string& method) {
  IntegratorOptions options;
  options.method = method;
  options.rtol = 1e-10;
  options.atol = 1e-12;
  SampledRun r;
  double t_last = -1.0;
  r.stats = integrate(problem, options, 0.0, {0.0}, 4.0, 0.05, [&](double t, double* y, double*) {
    EXPECT_GT(t, t_last);  // every sample once, in order, across both handovers
    t_last = t;
    r.worst = std::max(r.worst, std::abs(y[0] - std::sin(t)));
    ++r.samples;
    return ObserverAction::Continue;
  });
  return r;
}

TEST(StiffnessSwitch, StiffOnlyInAWindowReturnsToDop853) {
  const OdeProblem problem = stiff_window(1e6);
  const SampledRun automatic = run_window(problem, "auto");
  const std::string& method = automatic.stats.method;
  const size_t in = method.find(": cvode:jacobian from t = ");
  const size_t out = method.find(", not stiff at t = ");
  ASSERT_NE(in, std::string::npos) << method;
  ASSERT_NE(out, std::string::npos) << method;
  const size_t back = method.find(": dop853 from t = ", out);
  ASSERT_NE(back, std::string::npos) << method;
  EXPECT_EQ(method.find("stiff at t = ", back), std::string::npos) << method;  // two switches
  const double implicit_from = std::stod(method.substr(in + 26));
  const double explicit_from = std::stod(method.substr(back + 18));
  // into the window (w = 1e-3 at |t − 1.5| = 0.52) and out of it once k w h is small; the test
  // runs at fewer samples while it keeps failing (at most 32 apart: 1.6 s here)
  EXPECT_GT(implicit_from, 0.8) << method;
  EXPECT_LT(implicit_from, 1.3) << method;
  EXPECT_GT(explicit_from, 1.8) << method;
  EXPECT_LT(explicit_from, 3.5) << method;
  EXPECT_EQ(automatic.samples, 81);
  // as accurate as cvode:jacobian throughout (6.2e-6 from sin t at rtol 1e-10, measured), while
  // DOP853 throughout crawls through the window at h = 6.1 / (k w)
  const SampledRun implicit_only = run_window(problem, "cvode:jacobian");
  EXPECT_LT(automatic.worst, 1e-5);
  EXPECT_LT(implicit_only.worst, 1e-5);
  const SampledRun explicit_only = run_window(problem, "dop853");
  EXPECT_GT(explicit_only.stats.rhs_evals, 100 * automatic.stats.rhs_evals);
}

TEST(StiffnessSwitch, OscillatorStaysExplicit) {
  const test::Oscillator osc;
  IntegratorOptions options;
  options.method = "auto";
  double worst = 0.0;
  const IntegratorStats stats = integrate(
      osc.problem(), options, 0.0, {1.0, 0.0}, 50.0, 0.1, [&](double t, double* y, double*) {
        worst = std::max(worst, std::abs(y[0] - osc.x(t, 0.0, 1.0, 0.0)));
        return ObserverAction::Continue;
      });
  EXPECT_EQ(stats.method, "dop853");
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace lagrange
