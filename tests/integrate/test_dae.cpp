// IDA on index-1 DAEs with closed-form solutions, consistent-initial-condition correction,
// restarts, and failures.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "lagrange/error.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

using ::testing::HasSubstr;

// y1' = y2, 0 = y2 − cos t  ⇒  y2 = cos t, y1 = y1(0) + sin t.
DaeProblem sine_dae() {
  return {2,
          [](double t, const double* y, const double* yp, double* r) {
            r[0] = yp[0] - y[1];
            r[1] = y[1] - std::cos(t);
          },
          {true, false},
          {}};  // no Jacobian: Newton matrices from difference quotients
}

/// IDA options with the given tolerances.
IntegratorOptions ida_options(double rtol = 1e-10, double atol = 1e-12) {
  IntegratorOptions options;
  options.method = "ida";
  options.rtol = rtol;
  options.atol = atol;
  return options;
}

TEST(Ida, IndexOneDaeMatchesClosedForm) {
  std::vector<double> times;
  double worst = 0.0;
  const IntegratorStats stats = integrate_dae(
      sine_dae(), ida_options(), 0.0, {0.0, 1.0}, {1.0, 0.0}, 10.0, 0.1,
      [&](double t, double* y, double* yp) {
        times.push_back(t);
        worst = std::max({worst, std::abs(y[0] - std::sin(t)), std::abs(y[1] - std::cos(t)),
                          std::abs(yp[0] - std::cos(t))});
        return ObserverAction::Continue;
      });
  EXPECT_LT(worst, 1e-6);
  ASSERT_EQ(times.size(), 101u);
  EXPECT_EQ(times.back(), 10.0);
  EXPECT_GT(stats.steps, 0);
  EXPECT_GE(stats.rhs_evals, stats.steps);
}

TEST(Ida, InconsistentInitialValuesAreCorrected) {
  double y2_at_start = 0.0, yp1_at_start = 0.0, y1_at_start = -1.0, worst = 0.0;
  integrate_dae(sine_dae(), ida_options(), 0.0, {0.5, 0.9}, {0.8, 0.3}, 5.0, 0.5,
                [&](double t, double* y, double* yp) {
                  if (t == 0.0) {
                    y1_at_start = y[0];
                    y2_at_start = y[1];
                    yp1_at_start = yp[0];
                  }
                  worst = std::max(worst, std::abs(y[0] - (0.5 + std::sin(t))));
                  return ObserverAction::Continue;
                });
  EXPECT_EQ(y1_at_start, 0.5);  // differential components are kept
  EXPECT_NEAR(y2_at_start, 1.0, 1e-9);
  EXPECT_NEAR(yp1_at_start, 1.0, 1e-9);
  EXPECT_LT(worst, 1e-6);
}

TEST(Ida, StateChangedRestartsAndStopStops) {
  std::vector<double> after_reset;
  integrate_dae(sine_dae(), ida_options(), 0.0, {0.0, 1.0}, {1.0, 0.0}, 4.0, 0.25,
                [&](double t, double* y, double*) {
                  if (t == 1.0) {
                    y[0] = 10.0;  // y1 jumps; y2 stays consistent
                    return ObserverAction::StateChanged;
                  }
                  if (t > 1.0) after_reset.push_back(y[0] - (10.0 + std::sin(t) - std::sin(1.0)));
                  return t >= 3.0 ? ObserverAction::Stop : ObserverAction::Continue;
                });
  ASSERT_EQ(after_reset.size(), 8u);  // 1.25 … 3.0, then Stop
  for (double e : after_reset) EXPECT_LT(std::abs(e), 1e-6);
}

TEST(Ida, ResidualExceptionPropagatesWithItsTime) {
  DaeProblem problem = sine_dae();
  problem.residual = [](double t, const double* y, const double* yp, double* r) {
    if (t > 2.0) throw SimulationError(t, "constraint lost");
    r[0] = yp[0] - y[1];
    r[1] = y[1] - std::cos(t);
  };
  try {
    integrate_dae(problem, ida_options(), 0.0, {0.0, 1.0}, {1.0, 0.0}, 5.0, 0.5, Observer());
    FAIL() << "no exception";
  } catch (const SimulationError& e) {
    EXPECT_GT(e.time(), 2.0);
    EXPECT_LT(e.time(), 2.5);
    EXPECT_THAT(std::string(e.what()), HasSubstr("constraint lost"));
  }
}

TEST(Ida, TooFewStepsNameTheSundialsFlag) {
  IntegratorOptions options = ida_options();
  options.max_steps = 5;
  try {
    integrate_dae(sine_dae(), options, 0.0, {0.0, 1.0}, {1.0, 0.0}, 10.0, 10.0, Observer());
    FAIL() << "no exception";
  } catch (const SimulationError& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("IDA_TOO_MUCH_WORK"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("IDASolve"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("mxstep steps taken"));  // SUNDIALS' own message
    EXPECT_GT(e.time(), 0.0);
    EXPECT_LT(e.time(), 10.0);
  }
}

TEST(Ida, NanResidualIsASimulationError) {
  DaeProblem problem = sine_dae();
  problem.residual = [](double t, const double* y, const double* yp, double* r) {
    r[0] = yp[0] - y[1];
    r[1] = t > 1.0 ? std::nan("") : y[1] - std::cos(t);
  };
  EXPECT_THROW(
      integrate_dae(problem, ida_options(), 0.0, {0.0, 1.0}, {1.0, 0.0}, 5.0, 0.5, Observer()),
      SimulationError);
}

TEST(Ida, ArgumentsAreChecked) {
  EXPECT_THROW(
      integrate_dae(sine_dae(), ida_options(), 0.0, {0.0}, {1.0, 0.0}, 1.0, 0.1, Observer()),
      std::invalid_argument);
  DaeProblem no_id = sine_dae();
  no_id.differential = {true};
  EXPECT_THROW(
      integrate_dae(no_id, ida_options(), 0.0, {0.0, 1.0}, {1.0, 0.0}, 1.0, 0.1, Observer()),
      std::invalid_argument);
  IntegratorOptions cvode = ida_options();
  cvode.method = "cvode";
  EXPECT_THROW(integrate_dae(sine_dae(), cvode, 0.0, {0.0, 1.0}, {1.0, 0.0}, 1.0, 0.1, Observer()),
               std::invalid_argument);
}

}  // namespace
}  // namespace lagrange
