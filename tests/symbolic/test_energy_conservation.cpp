// conserves_energy (src/symbolic/energy_conservation.cpp, docs/theory.md §8.2): which models have
// T + U as a constant of motion, so that simulate() may hold a run to it.

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "support/harness.hpp"

namespace lagrange {
namespace {

bool conservative(const std::string& yaml) {
  const Model m = read_model_string(yaml, "<test>");
  return conserves_energy(derive(m));
}

const std::string kOscillator = "coordinates:\n  x: {initial: 1}\n";

TEST(EnergyConservation, ExamplesWithoutForcesConserveTheirEnergy) {
  for (const char* name : {"pendulum.yaml", "double_pendulum.yaml", "heavy_top.yaml",
                           "constrained_pendulum.yaml", "elastic_pendulum.yaml"}) {
    SCOPED_TRACE(name);
    auto sys = testing::load_example(name);
    EXPECT_TRUE(sys.compiled->conservative);
    // and they do: T + U at the end of a second equals its start to the tolerance
    const Trajectory tr = sys.run(testing::tight(sys, 1.0, 0.1));
    ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
    const double e0 = tr.at(0, "energy"), e1 = tr.at(tr.rows() - 1, "energy");
    EXPECT_NEAR(e1, e0, 1e-7 * (1 + std::abs(e0)));
  }
}

TEST(EnergyConservation, WorkFromOutsideOrTimeMakesItNoConstant) {
  EXPECT_FALSE(testing::load_example("spring_mass_damper.yaml").compiled->conservative);
  EXPECT_FALSE(testing::load_example("planar_arm_pd.yaml").compiled->conservative);
  EXPECT_TRUE(conservative(kOscillator + "kinetic: der(x)^2/2\npotential: x^2/2\n"));
  // explicit time in U or T
  EXPECT_FALSE(conservative(kOscillator + "kinetic: der(x)^2/2\npotential: (1 + t)*x^2/2\n"));
  EXPECT_FALSE(conservative(kOscillator + "kinetic: (2 + sin(t))*der(x)^2/2\n"));
  // a generalised force
  EXPECT_FALSE(conservative(kOscillator + "kinetic: der(x)^2/2\ngeneralized_forces: {x: -x}\n"));
}

TEST(EnergyConservation, TIsTheEnergyOnlyWhenQuadraticInTheVelocities) {
  // L = ẋ²/2 + x ẋ − x²/2: x ẋ = d(x²/2)/dt changes nothing in the motion, but T + U is then
  // not the energy function Σ v ∂L/∂v − L = ẋ²/2 + x²/2.
  EXPECT_FALSE(conservative(kOscillator + "kinetic: der(x)^2/2 + x*der(x)\npotential: x^2/2\n"));
  // a position-dependent mass keeps T quadratic
  EXPECT_TRUE(conservative(kOscillator + "kinetic: (1 + x^2)*der(x)^2/2\npotential: x^2/2\n"));
}

// Issue 37 item 12: the test expands Σ v ∂T/∂v − 2T only within 10 000 terms (an upper bound
// computed first). (Σqᵢ²)²⁰ in T once took minutes and gigabytes here; now the model is not
// called conservative (its energy is not checked) and the answer is immediate. Below the bound
// the test is made as before.
TEST(EnergyConservation, AnExpansionBeyondTheBoundIsNotAttempted) {
  std::string coordinates = "coordinates:\n", sum, velocities;
  for (int i = 0; i < 6; ++i) {
    const std::string q = "q" + std::to_string(i);
    coordinates += "  " + q + ": {initial: 0.1}\n";
    sum += (i ? " + " : "") + q + "^2";
    velocities += (i ? " + der(" : "der(") + q + ")^2";
  }
  const auto start = std::chrono::steady_clock::now();
  EXPECT_FALSE(conservative(coordinates + "kinetic: (1 + (" + sum + ")^20)*(" + velocities +
                            ")/2\npotential: 0\n"));
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_TRUE(conservative(coordinates + "kinetic: (1 + (" + sum + ")^2)*(" + velocities +
                           ")/2\npotential: 0\n"));
}

}  // namespace
}  // namespace lagrange
