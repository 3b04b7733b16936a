// The observer contract: StateChanged restarts from the modified state, Stop ends the run.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "integrate/oscillator.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

using test::options_for;
using test::Oscillator;

struct Sample {
  double t, x, v;
};

class ObserverContract : public ::testing::TestWithParam<const char*> {};

// At t = 1 the observer sets x = 0 (keeping v); the rest must match a fresh run from that state
// (dt = 0.125 so both grids hit the same binary times) and the closed form restarted at t = 1.
TEST_P(ObserverContract, StateChangedRestartsFromTheNewState) {
  const Oscillator osc;
  const IntegratorOptions options = options_for(GetParam(), 1e-10, 1e-12);
  std::vector<Sample> continued;
  double v_at_reset = 0.0;
  integrate(osc.problem(), options, 0.0, {1.0, 0.0}, 3.0, 0.125, [&](double t, double* y, double*) {
    if (t == 1.0) {
      y[0] = 0.0;
      v_at_reset = y[1];
      continued.push_back({t, y[0], y[1]});
      return ObserverAction::StateChanged;
    }
    if (t > 1.0) continued.push_back({t, y[0], y[1]});
    return ObserverAction::Continue;
  });
  std::vector<Sample> fresh;
  integrate(osc.problem(), options, 1.0, {0.0, v_at_reset}, 3.0, 0.125,
            [&](double t, double* y, double*) {
              fresh.push_back({t, y[0], y[1]});
              return ObserverAction::Continue;
            });
  ASSERT_EQ(continued.size(), 17u);
  ASSERT_EQ(fresh.size(), continued.size());
  const double tol = std::string(GetParam()) == "rk4" ? 1e-6 : 1e-7;
  for (size_t k = 0; k < fresh.size(); ++k) {
    EXPECT_EQ(continued[k].t, fresh[k].t);
    EXPECT_NEAR(continued[k].x, fresh[k].x, 1e-12) << "t = " << fresh[k].t;
    EXPECT_NEAR(continued[k].v, fresh[k].v, 1e-12) << "t = " << fresh[k].t;
    EXPECT_NEAR(continued[k].x, osc.x(fresh[k].t, 1.0, 0.0, v_at_reset), tol);
  }
}

TEST_P(ObserverContract, StopEndsTheRunAndReturnsTheStatsSoFar) {
  const Oscillator osc;
  const IntegratorOptions options = options_for(GetParam());
  std::vector<double> times;
  const IntegratorStats partial = integrate(
      osc.problem(), options, 0.0, {1.0, 0.0}, 10.0, 0.5, [&](double t, double*, double*) {
        times.push_back(t);
        return t >= 2.0 ? ObserverAction::Stop : ObserverAction::Continue;
      });
  EXPECT_EQ(times, (std::vector<double>{0.0, 0.5, 1.0, 1.5, 2.0}));
  const IntegratorStats full =
      integrate(osc.problem(), options, 0.0, {1.0, 0.0}, 10.0, 0.5,
                [](double, double*, double*) { return ObserverAction::Continue; });
  EXPECT_GT(partial.steps, 0);
  EXPECT_LT(partial.steps, full.steps);
}

TEST_P(ObserverContract, StopAtTheFirstSampleTakesNoStep) {
  const Oscillator osc;
  const IntegratorStats stats =
      integrate(osc.problem(), options_for(GetParam()), 0.0, {1.0, 0.0}, 10.0, 0.5,
                [](double, double*, double*) { return ObserverAction::Stop; });
  EXPECT_EQ(stats.steps, 0);
}

TEST_P(ObserverContract, EmptyObserverIsAllowed) {
  const Oscillator osc;
  const IntegratorStats stats =
      integrate(osc.problem(), options_for(GetParam()), 0.0, {1.0, 0.0}, 1.0, 0.5, Observer());
  EXPECT_GT(stats.steps, 0);
}

INSTANTIATE_TEST_SUITE_P(Methods, ObserverContract,
                         ::testing::Values("arkode", "dop853", "cvode", "rk4"));

}  // namespace
}  // namespace lagrange
