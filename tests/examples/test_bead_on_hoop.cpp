// examples/bead_on_hoop.yaml against its closed forms: θ̈ = sin θ (W² cos θ − g/R) rests at the
// relative equilibrium cos θ* = g / (W² R), oscillates about it at ω = W sin θ*, and keeps the
// Jacobi integral ½ m R² (θ̇² − W² sin²θ) − m g R cos θ (the energy is not conserved: the motor
// turning the hoop works on the bead).

#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.hpp"

namespace lagrange {
namespace {

constexpr double kR = 0.5, kW = 6.0, kG = 9.81;

TEST(BeadOnHoop, RestsAtTheRelativeEquilibriumCosThetaEqualsGOverOmegaSquaredR) {
  auto sys = testing::load_example("bead_on_hoop.yaml");
  const double star = std::acos(kG / (kW * kW * kR));
  const Trajectory tr = simulate(*sys.dynamics, testing::tight(sys, 5.0, 0.05), {star}, {0.0});
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  for (size_t r = 0; r < tr.rows(); ++r) ASSERT_NEAR(tr.at(r, "theta"), star, 1e-9);
  // Off the equilibrium it does not rest: the bottom (θ = 0.6) is pulled up towards θ*.
  const Trajectory off = simulate(*sys.dynamics, testing::tight(sys, 0.1, 0.1), {0.6}, {0.0});
  EXPECT_GT(off.at(off.rows() - 1, "theta"), 0.6 + 1e-3);
}

TEST(BeadOnHoop, SmallOscillationsAboutTheEquilibriumHaveOmegaEqualsWSinThetaStar) {
  auto sys = testing::load_example("bead_on_hoop.yaml");
  const double star = std::acos(kG / (kW * kW * kR));
  const double eps = 1e-4;  // the period's amplitude correction is O(eps²)
  const Trajectory tr =
      simulate(*sys.dynamics, testing::tight(sys, 6.0, 0.001), {star + eps}, {0.0});
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  // Upward crossings of θ*, located by linear interpolation between samples.
  std::vector<double> up;
  for (size_t r = 1; r < tr.rows(); ++r) {
    const double a = tr.at(r - 1, "theta") - star, b = tr.at(r, "theta") - star;
    if (a < 0 && b >= 0)
      up.push_back(tr.at(r - 1, "t") + (tr.at(r, "t") - tr.at(r - 1, "t")) * a / (a - b));
  }
  ASSERT_GE(up.size(), 3u);
  const double period = (up.back() - up.front()) / static_cast<double>(up.size() - 1);
  const double expected = 2 * M_PI / (kW * std::sin(star));
  EXPECT_NEAR(period / expected, 1.0, 1e-5) << period << " vs " << expected;
}

TEST(BeadOnHoop, TheShippedRunKeepsTheJacobiIntegralNotTheEnergy) {
  auto sys = testing::load_example("bead_on_hoop.yaml");
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double j0 = tr.at(0, "jacobi");
  double drift = 0, energy_change = 0;
  for (size_t r = 0; r < tr.rows(); ++r) {
    drift = std::max(drift, std::abs(tr.at(r, "jacobi") - j0));
    energy_change = std::max(energy_change, std::abs(tr.at(r, "energy") - tr.at(0, "energy")));
  }
  EXPECT_LT(drift, 1e-8 * std::abs(j0));
  EXPECT_GT(energy_change, 0.1 * std::abs(j0));
}

}  // namespace
}  // namespace lagrange
