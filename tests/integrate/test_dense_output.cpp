// Dense output: ARKODE, DOP853 and CVODE step freely and the samples come from their
// interpolants, so a finer output grid costs no extra steps, and an interpolated sample agrees with
// a run that stops exactly at that time.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "integrate/oscillator.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

using test::options_for;
using test::Oscillator;

/// The samples (x, v) of one run of the oscillator from (1, 0) on [0, t_end], every dt.
std::vector<double> samples(const IntegratorOptions& options, double t_end, double dt,
                            IntegratorStats* stats = nullptr) {
  const Oscillator osc;
  std::vector<double> out;
  const IntegratorStats s = integrate(osc.problem(), options, 0.0, {1.0, 0.0}, t_end, dt,
                                      [&](double, double* y, double*) {
                                        out.insert(out.end(), {y[0], y[1]});
                                        return ObserverAction::Continue;
                                      });
  if (stats) *stats = s;
  return out;
}

class DenseOutput : public ::testing::TestWithParam<const char*> {};

// The grid only decides where the interpolant is read: 10 000 samples take the same steps as 2.
TEST_P(DenseOutput, AFinerOutputGridTakesNoExtraSteps) {
  const IntegratorOptions options = options_for(GetParam(), 1e-8, 1e-10);
  IntegratorStats coarse, fine;
  samples(options, 10.0, 5.0, &coarse);
  samples(options, 10.0, 0.001, &fine);
  EXPECT_EQ(fine.steps, coarse.steps);
  // DOP853's continuous extension costs three evaluations in each step that holds a sample (its
  // stages 14–16); the other methods interpolate from what the steps computed anyway.
  const long extra = std::string(GetParam()) == "dop853" ? 3 * fine.steps : 0;
  EXPECT_LE(fine.rhs_evals, coarse.rhs_evals + extra);
  EXPECT_GE(fine.rhs_evals, coarse.rhs_evals);
  EXPECT_LT(coarse.steps, 2000) << "10 s of a 2 rad/s oscillator at rtol 1e-8";
}

// Each interpolated sample against a run that ends (stops) exactly there, at tight tolerance:
// the two differ by the interpolant's error, which is far below the error the steps make over
// the run (about rtol here), and both are close to the closed form.
TEST_P(DenseOutput, InterpolatedSamplesMatchRunsThatStopThere) {
  const IntegratorOptions options = options_for(GetParam(), 1e-11, 1e-13);
  const Oscillator osc;
  const double dt = 0.37;
  const std::vector<double> dense = samples(options, 3.0, dt);
  ASSERT_EQ(dense.size(), 2u * 10u);
  double worst = 0.0;
  for (size_t k = 1; k < 9; ++k) {
    const double t = static_cast<double>(k) * dt;
    const std::vector<double> stopped = samples(options, t, t);  // one interval: t is a stop
    ASSERT_EQ(stopped.size(), 4u);
    worst = std::max(
        {worst, std::abs(dense[2 * k] - stopped[2]), std::abs(dense[2 * k + 1] - stopped[3])});
    EXPECT_NEAR(dense[2 * k], osc.x(t, 0.0, 1.0, 0.0), 1e-8) << "t = " << t;
  }
  EXPECT_LT(worst, 1e-9);
  RecordProperty("largest_difference", std::to_string(worst));
}

INSTANTIATE_TEST_SUITE_P(Methods, DenseOutput,
                         ::testing::Values("arkode", "arkode:dormand-prince", "arkode:verner65",
                                           "arkode:verner87", "dop853", "cvode"));

// The step hook sees the internal steps in order (CVODE: those that reach a sample); a change it
// makes is where the run continues: here x is set to 0 after the first step past t = 1, and the end
// state must be the closed form restarted from there.
TEST(StepHook, ChangesMadeAfterAStepAreWhereTheRunContinues) {
  const Oscillator osc;
  for (const char* method : {"arkode", "dop853", "cvode", "rk4", "midpoint"}) {
    IntegratorOptions options = options_for(method, 1e-10, 1e-12);
    options.step = 0.001;
    long calls = 0;
    double last_t = 0.0, t_changed = -1.0, v_changed = 0.0;
    options.after_step = [&](double t, double* y) {
      EXPECT_GT(t, last_t) << method;
      last_t = t;
      ++calls;
      if (t_changed >= 0.0 || t < 1.0) return false;
      t_changed = t;
      v_changed = y[1];
      y[0] = 0.0;
      return true;
    };
    double x_end = 0.0;
    const IntegratorStats stats = integrate(osc.problem(), options, 0.0, {1.0, 0.0}, 2.0, 0.5,
                                            [&](double t, double* y, double*) {
                                              if (t == 2.0) x_end = y[0];
                                              return ObserverAction::Continue;
                                            });
    // CVODE offers only the first step past each sample (its restart is costly), the others all.
    EXPECT_GE(calls, std::string(method) == "cvode" ? 3 : stats.steps - 1) << method;
    ASSERT_GE(t_changed, 1.0) << method;
    EXPECT_NEAR(x_end, osc.x(2.0, t_changed, 0.0, v_changed), 1e-6) << method;
  }
}

}  // namespace
}  // namespace lagrange
