// The energy balance optimize() reports (docs/theory.md §10, "Checks"): H(T) − H(0) against each
// source's work over [0, T]. Closed forms from the boundary states, the damper's dissipation
// from the trajectory itself, and the pendulum's swing-up in two formulations.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lagrange/energy_balance.hpp"
#include "lagrange/reader.hpp"
#include "optimize/optimal_problem.hpp"

namespace lagrange {
namespace {

using testing::column;

double work_of(const EnergyBalance& e, const std::string& prefix) {
  for (const auto& [name, w] : e.work)
    if (name.rfind(prefix, 0) == 0) return w;
  ADD_FAILURE() << "no source '" << prefix << "…'";
  return NAN;
}

// Work–energy: from rest at x = 0 to speed 1 at x = 1, H gains ½ m + ½ k = 2 exactly; u's work
// minus the damper's c ∫ẋ² makes it up, and the damper's work is −c Σ h b_j ẋ_j² recomputed
// from the collocated velocities.
TEST(EnergyBalance, ForceAndDamperWorkMakeUpTheSpringMassEnergyGained) {
  testing::OptimalProblem p("data/spring_damper_to_speed.yaml");
  const OptimizeResult r = p.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  const EnergyBalance& e = r.energy_balance;
  ASSERT_TRUE(e.unsuitable.empty()) << e.unsuitable;
  ASSERT_EQ(e.work.size(), 2u);
  EXPECT_NEAR(e.change, 2.0, 1e-9);
  const double damper = work_of(e, "damper 'anchor'–'mass'");
  const double b[3] = {(16 - std::sqrt(6.0)) / 36, (16 + std::sqrt(6.0)) / 36, 1.0 / 9};
  const std::vector<double> v = column(r.trajectory, "x_dot");
  const double h = 1.0 / r.intervals;
  double dissipated = 0.0;
  for (size_t row = 1; row < v.size(); ++row) dissipated += h * b[(row - 1) % 3] * v[row] * v[row];
  EXPECT_NEAR(damper, -0.5 * dissipated, 1e-12);
  EXPECT_LT(damper, -0.1);
  EXPECT_NEAR(work_of(e, "force at 'mass'") + damper, 2.0, 1e-8);
  EXPECT_LT(e.relative_residual(), 1e-8);
}

// The swing-up gains 2 m g l from hanging at rest to upright at rest, all of it the force's
// work; the polar angle and the Cartesian bob on its rod agree.
TEST(EnergyBalance, PendulumSwingUpGainsTwoMglInBothFormulations) {
  const double gained = 2 * 1.0 * 9.81 * 1.0;
  double works[2];
  int i = 0;
  for (const char* file : {"pendulum_swing_up_polar.yaml", "pendulum_swing_up_cartesian.yaml"}) {
    testing::OptimalProblem p(file);
    const OptimizeResult r = p.solve();
    ASSERT_TRUE(r.optimal) << file << ": " << r.status;
    const EnergyBalance& e = r.energy_balance;
    ASSERT_TRUE(e.unsuitable.empty()) << e.unsuitable;
    EXPECT_NEAR(e.change, gained, 1e-4 * gained) << file;  // Cartesian: the implied final y
    works[i++] = work_of(e, "force at 'bob'");
    EXPECT_LT(e.relative_residual(), 1e-4) << file;
  }
  EXPECT_NEAR(works[0], gained, 1e-4 * gained);
  EXPECT_NEAR(works[1], works[0], 1e-4 * gained);
}

// A free body's torque: the attitude slew turns from rest to rest, so the torque's work over
// the slew is zero though it moved energy in and out.
TEST(EnergyBalance, TheSlewsTorqueGivesBackWhatItPutIn) {
  testing::OptimalProblem p("attitude_slew.yaml");
  const OptimizeResult r = p.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  const EnergyBalance& e = r.energy_balance;
  EXPECT_NEAR(e.change, 0.0, 1e-12);
  EXPECT_NEAR(work_of(e, "torque on 'sat'"), 0.0, 1e-9 * e.scale);
  EXPECT_GT(e.scale, 1e-3);  // the largest kinetic energy of the slew
}

// When the energies or the constraints depend on t or an input, the driver does work the
// sources do not show: no balance, and why.
TEST(EnergyBalance, ADrivenSpringIsNotBalancedAndSaysWhy) {
  const Model m = read_model_string(R"(name: driven
parameters: {k: 1.0}
coordinates:
  x: {initial: 0, rate: 0}
inputs:
  s: 0
kinetic: der(x)^2/2
potential: k/2*(x - s)^2
)",
                                    "driven.yaml");
  const Equations eq = derive(m);
  EXPECT_EQ(energy_balance_unsuitable(eq),
            "the energies depend on the input 's', whose driver does work");
  const Model rotor = read_model_string(R"(name: rotor
coordinates:
  x: {initial: 1, rate: 0}
  y: {initial: 0, rate: 0}
points:
  p: [x, y, 0]
particles:
  - {point: p, mass: 1}
constraints:
  guide: x*sin(t) - y*cos(t)
)",
                                        "rotor.yaml");
  EXPECT_EQ(energy_balance_unsuitable(derive(rotor)),
            "constraint 'guide' depends on t, whose driver does work");
}

// The energy function is the Jacobi integral Σ v ∂L/∂v − L: for a written kinetic energy with a
// term linear in the rate (a bead on a rotating wire written in the rotating frame), not T + U.
TEST(EnergyBalance, TheEnergyFunctionIsJacobisIntegral) {
  const Model m = read_model_string(R"(name: bead
parameters: {w: 2.0}
coordinates:
  r: {initial: 1, rate: 0}
kinetic: (der(r)^2 + w^2*r^2)/2 + w*der(r)
potential: r^2
)",
                                    "bead.yaml");
  const Equations eq = derive(m);
  const GiNaC::symbol& r = eq.kin.q[0];
  const GiNaC::symbol& v = eq.kin.v[0];
  const GiNaC::ex w = m.parameters.at(0).sym;
  // H = ½ v² − ½ w² r² + r² (the linear term drops out)
  EXPECT_TRUE(simplify(energy_function(eq) - (v * v / 2 - w * w * r * r / 2 + r * r)).is_zero())
      << energy_function(eq);
  EXPECT_TRUE(power_sources(eq).empty());
}

}  // namespace
}  // namespace lagrange
