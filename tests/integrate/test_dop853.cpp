// DOP853 (src/integrate/dop853.cpp): its continuous extension keeps the samples between steps at
// the method's accuracy (the error falls like h⁸ at fixed steps, where the cubic Hermite
// interpolant of the step ends would fall like h⁴), its error control meets the tolerance, and it
// stops with the time and the reason when the step size collapses.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "integrate/oscillator.hpp"
#include "lagrange/error.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

using test::options_for;
using test::Oscillator;
using ::testing::HasSubstr;

/// Largest |x − x_exact| over samples every 0.37 (between step ends) at the fixed step h, and
/// the same at the step ends (an output step equal to h).
struct SampledErrors {
  double between = 0.0, at_steps = 0.0;
};

SampledErrors errors_at_fixed_step(double h) {
  const Oscillator osc;
  IntegratorOptions options = options_for("dop853");
  options.step = h;
  SampledErrors e;
  const auto run = [&](double dt, double& worst) {
    integrate(osc.problem(), options, 0.0, {1.0, 0.0}, 4.0, dt, [&](double t, double* y, double*) {
      worst = std::max(worst, std::abs(y[0] - osc.x(t, 0.0, 1.0, 0.0)));
      return ObserverAction::Continue;
    });
  };
  run(0.37, e.between);
  run(h, e.at_steps);
  return e;
}

// From h = 0.25 to 0.125 (ωh = 0.5, 0.25) both errors fall by 2⁸ (slope 8 ± 0.3; at 0.0625 the
// step ends reach rounding): the interpolant's own error (local,
// of order h⁸ for an extension of order 7) does not lower the order of what the samples show,
// and stays within a small factor of the error the steps themselves carry.
TEST(Dop853, SamplesBetweenStepsConvergeAtOrderEight) {
  std::vector<SampledErrors> e;
  for (double h : {0.25, 0.125}) e.push_back(errors_at_fixed_step(h));
  for (size_t i = 0; i + 1 < e.size(); ++i) {
    const double slope_between = std::log2(e[i].between / e[i + 1].between);
    const double slope_steps = std::log2(e[i].at_steps / e[i + 1].at_steps);
    RecordProperty("slope_between_" + std::to_string(i), std::to_string(slope_between));
    EXPECT_NEAR(slope_between, 8.0, 0.3) << e[i].between << " " << e[i + 1].between;
    EXPECT_NEAR(slope_steps, 8.0, 0.3) << e[i].at_steps << " " << e[i + 1].at_steps;
    EXPECT_LT(e[i].between, 4.0 * e[i].at_steps);
  }
  EXPECT_GT(e.back().between, 1e-14) << "at rounding level: the slope would mean nothing";
}

// Adaptive runs of 20 s at rtol 10⁻⁴ … 10⁻¹⁰: the error against the closed form over samples
// every 0.01 s stays within a modest multiple of the tolerance (global error accumulates over
// about 6 periods), and tightening the tolerance 100-fold costs at most 1.9× the evaluations
// (order 8: 100^(1/8) = 1.78).
TEST(Dop853, AdaptiveErrorFollowsTheTolerance) {
  const Oscillator osc;
  long previous_evals = 0;
  for (double rtol : {1e-4, 1e-6, 1e-8, 1e-10}) {
    double worst = 0.0;
    const IntegratorStats stats =
        integrate(osc.problem(), options_for("dop853", rtol, rtol * 1e-2), 0.0, {1.0, 0.0}, 20.0,
                  0.01, [&](double t, double* y, double*) {
                    worst = std::max(worst, std::abs(y[0] - osc.x(t, 0.0, 1.0, 0.0)));
                    return ObserverAction::Continue;
                  });
    EXPECT_LT(worst, 50.0 * rtol) << "rtol " << rtol;
    EXPECT_GT(worst, 1e-3 * rtol) << "rtol " << rtol << ": suspiciously exact";
    if (previous_evals > 0) {
      EXPECT_LT(stats.rhs_evals, 1.9 * previous_evals) << rtol;
    }
    previous_evals = stats.rhs_evals;
  }
}

// y' = y² from y(0) = 1 is 1/(1 − t), which leaves every bound at t = 1: the run stops there
// with the time and why, instead of stepping past the singularity.
TEST(Dop853, CollapsingStepSizeStopsAtTheSingularity) {
  const OdeProblem blow_up{
      1, [](double, const double* y, double* ydot) { ydot[0] = y[0] * y[0]; }, {}};
  try {
    integrate(blow_up, options_for("dop853"), 0.0, {1.0}, 2.0, 0.1,
              [](double, double*, double*) { return ObserverAction::Continue; });
    FAIL() << "no exception";
  } catch (const SimulationError& e) {
    EXPECT_GT(e.time(), 0.99);
    EXPECT_LT(e.time(), 1.0 + 1e-6);  // y ≈ 10⁹ there: the last steps straddle t = 1
    const std::string what = e.what();
    RecordProperty("message", what);
    // Either the step size collapses first, or y overflows to inf in a stage.
    EXPECT_TRUE(what.find("step size fell") != std::string::npos ||
                what.find("is not finite") != std::string::npos)
        << what;
  }
}

// With atol = 0 a component that is exactly 0 has no error scale: the run stops at once and says
// so (instead of dividing by zero and collapsing the step size).
TEST(Dop853, ZeroAbsoluteToleranceOnAZeroComponentIsExplained) {
  const Oscillator osc;
  try {
    integrate(osc.problem(), options_for("dop853", 1e-8, 0.0), 0.0, {1.0, 0.0}, 1.0, 0.1,
              [](double, double*, double*) { return ObserverAction::Continue; });
    FAIL() << "no exception";
  } catch (const SimulationError& e) {
    EXPECT_EQ(e.time(), 0.0);
    EXPECT_THAT(std::string(e.what()), HasSubstr("y[1] = 0 with atol = 0"));
  }
}

}  // namespace
}  // namespace lagrange
