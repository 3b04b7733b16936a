// Failures: exceptions thrown by the right-hand side cross SUNDIALS intact, NaN is an error (not a
// hang), exhausted step budgets name the SUNDIALS flag, bad arguments are invalid_argument.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>

#include "integrate/oscillator.hpp"
#include "lagrange/error.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

using test::options_for;
using test::Oscillator;
using ::testing::HasSubstr;

/// Runs `fn`, expecting a SimulationError, and returns it.
template <class Fn>
SimulationError expect_simulation_error(Fn&& fn) {
  try {
    fn();
  } catch (const SimulationError& e) {
    return e;
  }
  ADD_FAILURE() << "no SimulationError";
  return SimulationError(std::nan(""), "none");
}

const Observer kContinue = [](double, double*, double*) { return ObserverAction::Continue; };

class OdeFailures : public ::testing::TestWithParam<const char*> {};

TEST_P(OdeFailures, RhsSimulationErrorPropagatesWithItsTime) {
  const OdeProblem problem{1,
                           [](double t, const double* y, double* ydot) {
                             if (t > 2.0) throw SimulationError(t, "mass matrix is singular");
                             ydot[0] = -y[0];
                           },
                           {}};
  const SimulationError e = expect_simulation_error(
      [&] { integrate(problem, options_for(GetParam()), 0.0, {1.0}, 5.0, 0.5, kContinue); });
  EXPECT_GT(e.time(), 2.0);
  EXPECT_LT(e.time(), 2.5);
  EXPECT_THAT(std::string(e.what()), HasSubstr("mass matrix is singular"));
}

TEST_P(OdeFailures, OtherExceptionsKeepTheirType) {
  const OdeProblem problem{
      1, [](double t, const double*, double*) { throw std::out_of_range("index 7"); }, {}};
  EXPECT_THROW(integrate(problem, options_for(GetParam()), 0.0, {1.0}, 1.0, 0.5, kContinue),
               std::out_of_range);
}

TEST_P(OdeFailures, NanInTheRhsIsASimulationError) {
  const OdeProblem problem{2,
                           [](double t, const double* y, double* ydot) {
                             ydot[0] = y[1];
                             ydot[1] = t > 1.0 ? std::numeric_limits<double>::quiet_NaN() : -y[0];
                           },
                           {}};
  const SimulationError e = expect_simulation_error([&] {
    integrate(problem, options_for(GetParam()), 0.0, {1.0, 0.0}, 5.0, 0.5, kContinue);
  });
  EXPECT_GT(e.time(), 1.0);
  EXPECT_LT(e.time(), 1.5);
  EXPECT_THAT(std::string(e.what()), HasSubstr("ydot[1] = nan is not finite"));
}

INSTANTIATE_TEST_SUITE_P(Methods, OdeFailures,
                         ::testing::Values("arkode", "dop853", "cvode", "rk4"));

TEST(OdeFailures, TooFewStepsNameTheSundialsFlag) {
  const Oscillator osc;
  for (const auto& [method, flag, call] :
       {std::tuple{"arkode", "ARK_TOO_MUCH_WORK", "ERKStepEvolve"},
        std::tuple{"dop853", "TOO_MUCH_WORK", "dop853"},
        std::tuple{"cvode", "CV_TOO_MUCH_WORK", "CVode"}}) {
    IntegratorOptions options = options_for(method);
    options.max_steps = 5;
    const SimulationError e = expect_simulation_error([&] {
      integrate(osc.problem(), options, 0.0, {1.0, 0.0}, 10.0, 10.0, kContinue);
    });
    EXPECT_THAT(std::string(e.what()), HasSubstr(flag));
    EXPECT_THAT(std::string(e.what()), HasSubstr(call));
    EXPECT_THAT(std::string(e.what()), HasSubstr("mxstep steps taken"));  // SUNDIALS' own message
    EXPECT_GT(e.time(), 0.0) << method;
    EXPECT_LT(e.time(), 10.0) << method;
  }
}

TEST(OdeArguments, UnknownMethodListsTheValidOnes) {
  const Oscillator osc;
  try {
    integrate(osc.problem(), options_for("euler"), 0.0, {1.0, 0.0}, 1.0, 0.1, kContinue);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(std::string(e.what()), HasSubstr("'euler'"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("arkode, arkode:heun-euler"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("arkode:verner65"));
    EXPECT_THAT(std::string(e.what()), HasSubstr("cvode, cvode:jacobian, auto, rk4, midpoint"));
  }
}

TEST(OdeArguments, BadSizesAndOptionsAreRejected) {
  const Oscillator osc;
  EXPECT_THROW(integrate(osc.problem(), options_for("arkode"), 0.0, {1.0}, 1.0, 0.1, kContinue),
               std::invalid_argument);
  IntegratorOptions bad = options_for("cvode", -1.0);
  EXPECT_THROW(integrate(osc.problem(), bad, 0.0, {1.0, 0.0}, 1.0, 0.1, kContinue),
               std::invalid_argument);
  bad = options_for("cvode");
  bad.max_steps = 0;
  EXPECT_THROW(integrate(osc.problem(), bad, 0.0, {1.0, 0.0}, 1.0, 0.1, kContinue),
               std::invalid_argument);
  for (int order : {0, 6}) {  // BDF has orders 1 to 5
    bad = options_for("cvode");
    bad.max_order = order;
    EXPECT_THROW(integrate(osc.problem(), bad, 0.0, {1.0, 0.0}, 1.0, 0.1, kContinue),
                 std::invalid_argument)
        << order;
  }
  EXPECT_THROW(integrate(osc.problem(), options_for("rk4"), 0.0, {1.0, 0.0}, 1.0, 0.0, kContinue),
               std::invalid_argument);
  // Counts beyond their bounds, before any step (issue 37 item 3): once a cast of 1e+99 to long
  // (undefined) for the fixed steps, and a grid of 1e+100 samples.
  for (const char* method : {"rk4", "midpoint"}) {
    bad = options_for(method);
    bad.step = 1e-100;
    EXPECT_THROW(integrate(osc.problem(), bad, 0.0, {1.0, 0.0}, 1.0, 0.1, kContinue),
                 std::invalid_argument)
        << method;
  }
  EXPECT_THROW(
      integrate(osc.problem(), options_for("dop853"), 0.0, {1.0, 0.0}, 1.0, 1e-100, kContinue),
      std::invalid_argument);
}

}  // namespace
}  // namespace lagrange
