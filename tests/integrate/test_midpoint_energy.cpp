// The implicit midpoint rule (`midpoint`) on the double pendulum: over 10⁶ fixed steps the energy
// error stays bounded (nowhere in the run larger than in its first hundredth, up to a factor),
// while an adaptive explicit method's error grows with time (its last tenth well above its first
// hundredth).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "integrate/double_pendulum.hpp"
#include "integrate/oscillator.hpp"
#include "lagrange/integrator.hpp"

namespace lagrange {
namespace {

using test::DoublePendulum;
using test::options_for;

// The same 10⁶ steps under AddressSanitizer (about 3 s there): the chaotic pendulum's energy
// error needs the first hundredth (100 s) to reach the size it keeps, so a shorter run would
// compare the plateau with a transient.
constexpr double kSteps = 1e6;

/// Largest |E − E0| in each hundredth of [0, t_end] (2000 samples).
std::vector<double> energy_error_by_hundredth(const IntegratorOptions& options, double t_end,
                                              IntegratorStats* stats) {
  const DoublePendulum pendulum;
  const std::vector<double> y0{1.2, 0.4, 0.0, 0.0};
  const double e0 = pendulum.energy(y0.data());
  std::vector<double> worst(100, 0.0);
  *stats = integrate(pendulum.problem(), options, 0.0, y0, t_end, t_end / 2000.0,
                     [&](double t, double* y, double*) {
                       const auto part = std::min<size_t>(99, static_cast<size_t>(100 * t / t_end));
                       worst[part] = std::max(worst[part], std::abs(pendulum.energy(y) - e0));
                       return ObserverAction::Continue;
                     });
  return worst;
}

/// The largest of worst[first..last).
double largest(const std::vector<double>& worst, size_t first, size_t last) {
  return *std::max_element(worst.begin() + static_cast<long>(first),
                           worst.begin() + static_cast<long>(last));
}

TEST(Midpoint, DoublePendulumEnergyErrorStaysBoundedOverAMillionSteps) {
  const double h = 0.01, t_end = kSteps * h;
  IntegratorOptions midpoint = options_for("midpoint");
  midpoint.step = h;
  IntegratorStats stats;
  const std::vector<double> bounded = energy_error_by_hundredth(midpoint, t_end, &stats);
  EXPECT_EQ(stats.steps, static_cast<long>(kSteps));
  const double start = bounded.front(), overall = largest(bounded, 0, 100);
  RecordProperty("midpoint_first_hundredth", std::to_string(start));
  RecordProperty("midpoint_last_tenth", std::to_string(largest(bounded, 90, 100)));
  EXPECT_LT(overall, 4.0 * start) << "no secular trend: the error stays at its early size";
  EXPECT_LT(overall, 5e-2) << "the h² error of a second-order method at h = 0.01";

  // The adaptive default at a loose tolerance over the same time: its error accumulates.
  IntegratorStats adaptive_stats;
  const std::vector<double> drifting =
      energy_error_by_hundredth(options_for("arkode", 1e-6, 1e-8), t_end, &adaptive_stats);
  RecordProperty("arkode_first_hundredth", std::to_string(drifting.front()));
  RecordProperty("arkode_last_tenth", std::to_string(largest(drifting, 90, 100)));
  EXPECT_GT(largest(drifting, 90, 100), 5.0 * drifting.front()) << "the adaptive method drifts";
}

}  // namespace
}  // namespace lagrange
