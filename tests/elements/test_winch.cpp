// Winches (src/elements/winch.cpp): the seed's winch example as an oracle, and the energy balance
// of drum, motor and the tether's mass moving between drum and air.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.hpp"

namespace lagrange {
namespace {

// Seed 000, "Example: Winch": (J + mR²) θ̈ − μ g R² θ = 0, so θ(t) = θ₀ cosh(ω t) from rest with
// ω² = μ g R² / (J + m R²), m = μ L. The engine's model is a 10-segment lumped tether with node
// masses μℓ/(N + 1) that depend on the winch's coordinate ℓ = R θ.
TEST(Winch, FollowsTheSeedsCoshSolution) {
  auto sys = testing::load_example("winch.yaml");
  const Trajectory tr = sys.run(testing::tight(sys, 1.5, 0.01));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double R = 0.2, J = 0.05, mu = 0.4, L = 30, g = 9.81, theta0 = 5;
  const double omega = std::sqrt(mu * g * R * R / (J + mu * L * R * R));
  for (size_t r = 0; r < tr.rows(); ++r) {
    const double t = tr.at(r, "t"), expected = theta0 * std::cosh(omega * t);
    ASSERT_NEAR(tr.at(r, "drum.angle"), expected, 1e-8 * expected) << "t = " << t;
    ASSERT_NEAR(tr.at(r, "drum.speed"), R * theta0 * omega * std::sinh(omega * t),
                1e-8 * R * expected * omega);
  }
  // The control volume (drum + tether) has constant mass: energy is conserved while mass moves.
  EXPECT_NEAR(tr.at(tr.rows() - 1, "energy"), tr.at(0, "energy"), 1e-9);
  EXPECT_GT(tr.at(tr.rows() - 1, "line.mass"), 1.3 * tr.at(0, "line.mass"));
}

std::string braked_winch(const std::string& torque) {
  return fmt::format(R"(parameters: {{g: 9.81, M: 2}}
gravity: [0, 0, -g]
coordinates:
  x: {{initial: 1.5}}
  y: {{initial: 0}}
  z: {{initial: -4}}
points:
  load: [x, y, z]
particles:
  load: M
winches:
  reel:
    tether: line
    radius: 0.1
    inertia: 0.02
    total_length: 20
    initial: {{reeled_out: 5, rate: 0.2}}
    torque: {}
tethers:
  line:
    between: [[0, 0, 0], load]
    segments: 6
    mass_per_length: 0.2
    diameter: 0.01
    drag: simple
)",
                     torque);
}

// d(T + U)/dt = P_motor + P_drag along a reel-out braked by the motor while the load swings:
// T holds the drum, the tether on it and the airborne tether with its reel-out velocity, so the
// mass moving from drum to air is in the balance (no separate mass-flow term remains).
TEST(Winch, EnergyChangeEqualsMotorAndDragWork) {
  auto sys = testing::load_string(braked_winch("-0.8*der(reel.reeled_out) - 1"));
  const Trajectory tr = sys.run(testing::tight(sys, 2, 0.001));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  double work = 0, flow = 0;
  for (size_t r = 1; r < tr.rows(); ++r) {
    const double dt = tr.at(r, "t") - tr.at(r - 1, "t");
    auto p = [&](size_t i) { return tr.at(i, "reel.power") + tr.at(i, "line.drag_power"); };
    work += dt * (p(r - 1) + p(r)) / 2;
    flow += dt * (std::abs(p(r - 1)) + std::abs(p(r))) / 2;
  }
  const double change = tr.at(tr.rows() - 1, "energy") - tr.at(0, "energy");
  EXPECT_GT(flow, 0.1);
  EXPECT_NEAR(change, work, 1e-5 * flow);
  EXPECT_GT(tr.at(tr.rows() - 1, "reel.reeled_out"), 5.0);  // the load pulls tether out
}

// A prescribed reel-out ℓ(t): the length follows it exactly and reel.power = −λ ℓ̇ is the power
// the reel takes from the tether.
TEST(Winch, PrescribedReelOutFollowsItsLength) {
  std::string yaml = braked_winch("0");
  const std::string from = "    initial: {reeled_out: 5, rate: 0.2}\n    torque: 0\n";
  yaml.replace(yaml.find(from), from.size(), "    reeled_out: 5 + 0.2*t\n");
  auto sys = testing::load_string(yaml);
  const Trajectory tr = sys.run(testing::tight(sys, 2, 0.01));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  for (size_t r = 0; r < tr.rows(); ++r)
    ASSERT_NEAR(tr.at(r, "reel.reeled_out"), 5 + 0.2 * tr.at(r, "t"), 1e-9);
  EXPECT_LT(tr.at(tr.rows() / 2, "reel.power"), 0.0);  // tension does work on the reel
}

}  // namespace
}  // namespace lagrange
