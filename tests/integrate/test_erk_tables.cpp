// Every named ARKODE table (`arkode:<name>`) reaches its nominal order on the harmonic oscillator:
// at fixed steps h, 2h, 4h the error at t = 2 falls like h^p (least-squares slope of log error
// against log h within ±0.3 of p). Plain `arkode` picks a table by tolerance. The embedding of
// Verner 8(7), which ARKODE only uses for its error estimate, reaches 7 when stepped on its own.

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "integrate/erk_coefficients.hpp"
#include "integrate/oscillator.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

using test::options_for;
using test::Oscillator;

struct Table {
  const char* method;
  int order;
  double h;  ///< the finest step: errors stay well above rounding, in the asymptotic range
};

const Table kTables[] = {
    {"arkode:heun-euler", 2, 0.005},
    {"arkode:bogacki-shampine", 3, 0.005},
    {"arkode:zonneveld", 4, 0.01},
    {"arkode:sayfy-aburub", 4, 0.01},
    {"arkode:cash-karp", 5, 0.02},
    {"arkode:fehlberg", 5, 0.02},
    {"arkode:dormand-prince", 5, 0.02},
    {"arkode:verner65", 6, 0.03},
    {"arkode:fehlberg78", 8, 0.125},
    {"arkode:verner87", 8, 0.125},
    {"dop853", 8, 0.125},
};

/// |x − x_exact| + |v − v_exact| at t = 2 for the oscillator from (1, 0) at fixed step h.
double error_at_fixed_step(const char* method, double h) {
  const Oscillator osc;
  IntegratorOptions options = options_for(method);
  options.step = h;
  double error = 0.0;
  integrate(osc.problem(), options, 0.0, {1.0, 0.0}, 2.0, 2.0, [&](double t, double* y, double*) {
    error = std::abs(y[0] - osc.x(t, 0.0, 1.0, 0.0)) + std::abs(y[1] - osc.v(t, 0.0, 1.0, 0.0));
    return ObserverAction::Continue;
  });
  return error;
}

/// Least-squares slope of log error against log h, from errors at h, 2h, 4h of `error_at`.
template <class ErrorAt>
double order_slope(double h, ErrorAt&& error_at, const char* what) {
  std::vector<double> log_h, log_e;
  for (double scale : {4.0, 2.0, 1.0}) {
    const double e = error_at(h * scale);
    EXPECT_GT(e, 1e-13) << what << " h = " << h * scale << ": at rounding level";
    log_h.push_back(std::log(h * scale));
    log_e.push_back(std::log(e));
  }
  const double mean_h = (log_h[0] + log_h[1] + log_h[2]) / 3.0;
  const double mean_e = (log_e[0] + log_e[1] + log_e[2]) / 3.0;
  double num = 0.0, den = 0.0;
  for (size_t i = 0; i < 3; ++i) {
    num += (log_h[i] - mean_h) * (log_e[i] - mean_e);
    den += (log_h[i] - mean_h) * (log_h[i] - mean_h);
  }
  return num / den;
}

class ErkTableOrder : public ::testing::TestWithParam<Table> {};

TEST_P(ErkTableOrder, SlopeOfLogErrorAgainstLogStepIsTheNominalOrder) {
  const Table table = GetParam();
  const double slope = order_slope(
      table.h, [&](double h) { return error_at_fixed_step(table.method, h); }, table.method);
  RecordProperty("slope", std::to_string(slope));
  EXPECT_NEAR(slope, table.order, 0.3) << table.method;
}

/// The same error for the explicit table (c, A) with weights w, stepped here at fixed step h.
double error_of_weights(const integration::ButcherCoefficients& k, const std::vector<double>& w,
                        double h) {
  const Oscillator osc;
  const OdeProblem problem = osc.problem();
  const size_t s = k.c.size();
  std::vector<std::vector<double>> f(s, std::vector<double>(2));
  std::vector<double> y{1.0, 0.0}, stage(2);
  const int steps = static_cast<int>(std::lround(2.0 / h));
  for (int n = 0; n < steps; ++n) {
    for (size_t i = 0; i < s; ++i) {
      stage = y;
      for (size_t j = 0; j < i; ++j)
        for (size_t m = 0; m < 2; ++m) stage[m] += h * k.a[i][j] * f[j][m];
      problem.rhs(n * h + k.c[i] * h, stage.data(), f[i].data());
    }
    for (size_t i = 0; i < s; ++i)
      for (size_t m = 0; m < 2; ++m) y[m] += h * w[i] * f[i][m];
  }
  const double t = steps * h;
  return std::abs(y[0] - osc.x(t, 0.0, 1.0, 0.0)) + std::abs(y[1] - osc.v(t, 0.0, 1.0, 0.0));
}

TEST(Verner87, EmbeddingReachesOrderSeven) {
  const integration::ButcherCoefficients& k = integration::verner_8_7();
  const double slope = order_slope(
      0.0625, [&](double h) { return error_of_weights(k, k.d, h); }, "embedding");
  RecordProperty("slope", std::to_string(slope));
  EXPECT_NEAR(slope, 7.0, 0.3);
  // The propagated weights, stepped the same way, reach 8 as ARKODE's steps do above.
  EXPECT_NEAR(order_slope(
                  0.125, [&](double h) { return error_of_weights(k, k.b, h); }, "b"),
              8.0, 0.3);
}

INSTANTIATE_TEST_SUITE_P(Tables, ErkTableOrder, ::testing::ValuesIn(kTables),
                         [](const ::testing::TestParamInfo<Table>& info) {
                           std::string name = info.param.method;
                           for (char& c : name)
                             if (c == '-' || c == ':') c = '_';
                           return name;
                         });

// Plain `arkode` runs the table docs/benchmarks.md chose for the tolerance, and says which.
TEST(IntegratorMethods, DefaultTableFollowsTheTolerance) {
  const Oscillator osc;
  const auto ran = [&](double rtol) {
    return integrate(osc.problem(), options_for("arkode", rtol, rtol / 100), 0.0, {1.0, 0.0}, 1.0,
                     0.5, [](double, double*, double*) { return ObserverAction::Continue; })
        .method;
  };
  EXPECT_EQ(ran(1e-4), "arkode:dormand-prince");
  EXPECT_EQ(ran(1e-5), "arkode:dormand-prince");
  EXPECT_EQ(ran(1e-6), "arkode:verner65");
  EXPECT_EQ(ran(1e-8), "arkode:verner65");
  EXPECT_EQ(ran(1e-12), "arkode:verner65");
}

// Every accepted ODE name runs, and the adaptive tables meet their tolerance.
TEST(IntegratorMethods, EveryListedOdeMethodIntegrates) {
  const Oscillator osc;
  size_t ode = 0;
  for (const std::string& method : integrator_methods()) {
    if (method == "ida" || method == "ida:jacobian") continue;  // DAE methods
    ++ode;
    double x_end = 0.0;
    integrate(osc.problem(), options_for(method.c_str(), 1e-9, 1e-11), 0.0, {1.0, 0.0}, 1.0, 0.25,
              [&](double t, double* y, double*) {
                if (t == 1.0) x_end = y[0];
                return ObserverAction::Continue;
              });
    EXPECT_NEAR(x_end, osc.x(1.0, 0.0, 1.0, 0.0), method == "midpoint" ? 1e-3 : 1e-5) << method;
  }
  EXPECT_GE(ode, 11u);
  EXPECT_NE(integrator_method_list().find("arkode:verner65"), std::string::npos);
}

}  // namespace
}  // namespace lagrange
