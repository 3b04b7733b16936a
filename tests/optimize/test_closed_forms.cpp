// Optimal control against closed forms (docs/theory.md §10): minimum energy and minimum time of
// the double integrator; the pendulum swing-up's convergence.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "optimize/optimal_problem.hpp"

namespace lagrange {
namespace {

// ∫u² with u constant on N intervals, rest to rest over 1 in T = 1: u_k = (6 − 12 t_k)/(1 − h²)
// at the midpoints t_k, J = 12/(1 − h²), h = 1/N (Lagrange conditions of the finite problem;
// N → ∞ gives the continuous u = 6 − 12t, J = 12). Radau of degree ≥ 2 integrates the piecewise
// quadratic x exactly, so the collocated optimum is this one.
TEST(OptimalControl, MinimumEnergyDoubleIntegratorMatchesTheClosedForm) {
  testing::OptimalProblem p("double_integrator_min_energy.yaml");
  for (int degree : {2, 3}) {
    const int N = 10;
    const OptimizeResult r = p.solve(N, degree);
    ASSERT_TRUE(r.optimal) << r.status;
    const double h = 1.0 / N;
    EXPECT_NEAR(r.objective, 12.0 / (1 - h * h), 1e-7) << "degree " << degree;
    for (int k = 0; k < N; ++k)
      EXPECT_NEAR(r.controls[static_cast<size_t>(k)], (6 - 12 * (k + 0.5) * h) / (1 - h * h), 1e-5)
          << "interval " << k;
    EXPECT_LT(r.violation, 1e-8);
  }
}

// |u| ≤ 1 over distance d: T = 2√d (bang-bang, switching at T/2, on the mesh for even N).
TEST(OptimalControl, MinimumTimeDoubleIntegratorIsTwiceTheSquareRootOfTheDistance) {
  for (double d : {1.0, 4.0}) {
    testing::OptimalProblem p("double_integrator_min_time.yaml", {{"d", d}});
    const OptimizeResult r = p.solve(10, 2);
    ASSERT_TRUE(r.optimal) << r.status;
    EXPECT_NEAR(r.horizon, 2 * std::sqrt(d), 1e-6) << "d = " << d;
    EXPECT_NEAR(r.objective, r.horizon, 1e-12);
    EXPECT_NEAR(r.controls.front(), 1.0, 1e-5);
    EXPECT_NEAR(r.controls.back(), -1.0, 1e-5);
    // Bang-bang: u on each bound on half the intervals, and nothing else bounded is reached.
    EXPECT_EQ(r.active_bounds, (std::vector<std::string>{"control 'u' ≥ -1 at 5 of 10 values",
                                                         "control 'u' ≤ 1 at 5 of 10 values"}));
  }
}

// mean(u²) over T = 2 is the minimum-energy optimum divided by T: 12 d²/T³ /(1 − 1/N²) / T, with
// the same controls, over a fixed horizon and as the limit of a free one pinned by its bounds.
TEST(OptimalControl, MeanIsTheIntegralOverTheHorizon) {
  testing::OptimalProblem p("double_integrator_min_energy.yaml");
  OptimalControlSpec& spec = *p.model->optimal_control;
  spec.horizon = 2.0;
  const OptimizeResult integral = p.solve(10, 3);
  spec.mean_integrand = spec.integrand;
  spec.integrand = 0;
  const OptimizeResult mean = p.solve(10, 3);
  ASSERT_TRUE(integral.optimal && mean.optimal) << integral.status << mean.status;
  const double closed = 12.0 / 8.0 / (1 - 1.0 / 100);
  EXPECT_NEAR(integral.objective, closed, 1e-9);
  EXPECT_NEAR(mean.objective, closed / 2, 1e-9);
  for (size_t k = 0; k < mean.controls.size(); ++k)
    EXPECT_NEAR(mean.controls[k], integral.controls[k], 1e-7);
  spec.free_horizon = Bounds{2.0, 2.0};
  const OptimizeResult pinned = p.solve(10, 3);
  ASSERT_TRUE(pinned.optimal) << pinned.status;
  EXPECT_NEAR(pinned.objective, closed / 2, 1e-7);
}

// The pendulum swing-up by a horizontal force: the optimum re-simulates onto the upright rest
// state to the collocation's accuracy, which improves with N.
TEST(OptimalControl, PendulumSwingUpConvergesWithTheMesh) {
  testing::OptimalProblem polar("pendulum_swing_up_polar.yaml");
  const OptimizeResult coarse = polar.solve(15, 3), fine = polar.solve(30, 3);
  ASSERT_TRUE(coarse.optimal) << coarse.status;
  ASSERT_TRUE(fine.optimal) << fine.status;
  // Piecewise-constant controls: the cost falls towards the continuous optimum as N doubles
  // (15 intervals' controls are also 30 intervals' controls).
  EXPECT_LT(fine.objective, coarse.objective);
  EXPECT_NEAR(coarse.objective, fine.objective, 0.06 * fine.objective);
  SimulationOptions so;
  so.integrator.rtol = 1e-11;
  so.integrator.atol = 1e-13;
  const VerifyResult vc = verify(*polar.dyn, polar.spec(), coarse, so);
  const VerifyResult vf = verify(*polar.dyn, polar.spec(), fine, so);
  EXPECT_LT(vf.final_gap, 1e-3);
  EXPECT_LT(vf.final_gap, vc.final_gap);
}

// Re-simulating the optimal piecewise controls lands where the collocation says.
TEST(OptimalControl, VerifyFindsTheCollocatedFinalState) {
  testing::OptimalProblem p("double_integrator_min_energy.yaml");
  const OptimizeResult r = p.solve(10, 3);
  ASSERT_TRUE(r.optimal);
  SimulationOptions so;
  so.integrator.rtol = 1e-11;
  so.integrator.atol = 1e-13;
  const VerifyResult v = verify(*p.dyn, p.spec(), r, so);
  EXPECT_TRUE(v.message.empty()) << v.message;
  EXPECT_LT(v.final_gap, 1e-8);
  EXPECT_LT(v.largest_gap, 1e-8);
}

// A constant control is a design value: the damping that minimises ∫ x² of the unit oscillator
// is c = 1 with ∫ x² = c/2 + 1/(2c) = 1 (data/optimal_damping.yaml), one value on every interval.
TEST(OptimalControl, AConstantControlFindsTheOptimalDamping) {
  testing::OptimalProblem p("data/optimal_damping.yaml");
  const OptimizeResult r = p.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  EXPECT_NEAR(r.objective, 1.0, 1e-6);
  ASSERT_EQ(r.controls.size(), static_cast<size_t>(r.intervals));
  for (const double c : r.controls) EXPECT_NEAR(c, 1.0, 1e-4);
  // As a per-interval control the same problem does better than any single damping.
  p.model->optimal_control->controls[0].constant = false;
  const OptimizeResult free = p.solve();
  ASSERT_TRUE(free.optimal) << free.status;
  EXPECT_LT(free.objective, r.objective - 0.05);
}

}  // namespace
}  // namespace lagrange
