// Polynomial controls (docs/theory.md §10, "Polynomial controls"): the minimum-energy double
// integrator's linear optimum represented exactly, the exact derivatives with polynomial controls,
// re-simulation along the polynomials, and the reader's refusal of `constant` with `polynomial`.

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "optimize/nlp_derivative_check.hpp"
#include "optimize/optimal_problem.hpp"

namespace lagrange {
namespace {

/// Every control of the problem that is not constant over the horizon made polynomial.
void make_polynomial(testing::OptimalProblem& p) {
  for (ControlSpec& c : p.model->optimal_control->controls) c.polynomial = !c.constant;
}

// Rest to rest over 1 in T = 1 minimising ∫u²: u = 6 − 12t, x = 3t² − 2t³, J = 12. A polynomial
// control of degree d − 1 ≥ 1 holds the linear u and the collocation state of degree d ≥ 3 the
// cubic x, so already N = 2 gives J = 12; a piecewise-constant u gives 12/(1 − 1/N²) = 16.
TEST(PolynomialControls, MinimumEnergyDoubleIntegratorIsExactAtTwoIntervals) {
  testing::OptimalProblem p("data/double_integrator_polynomial.yaml");
  ASSERT_TRUE(p.spec().controls[0].polynomial);
  const OptimizeResult r = p.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  ASSERT_EQ(r.intervals, 2);
  ASSERT_EQ(r.degree, 3);
  EXPECT_NEAR(r.objective, 12.0, 1e-8);
  ASSERT_EQ(r.control_points.size(), 6u);
  const Trajectory& traj = r.trajectory;
  const size_t cols = traj.columns.size(), u = cols - 1;  // the control is the last column
  ASSERT_EQ(traj.columns[u], "u");
  for (size_t row = 0; row < traj.rows(); ++row) {
    const double t = traj.data[row * cols];
    EXPECT_NEAR(traj.data[row * cols + u], 6 - 12 * t, 1e-7) << "t = " << t;
    if (row > 0) {
      EXPECT_EQ(traj.data[row * cols + u], r.control_points[row - 1]);
    }
    EXPECT_NEAR(traj.data[row * cols + 1], 3 * t * t - 2 * t * t * t, 1e-9) << "t = " << t;
  }
  // The interval means of 6 − 12t: 3 and −3.
  EXPECT_NEAR(r.controls[0], 3.0, 1e-7);
  EXPECT_NEAR(r.controls[1], -3.0, 1e-7);
  double u_half = 0.0;  // between collocation points, the polynomial
  controls_at(r, 0.3, &u_half);
  EXPECT_NEAR(u_half, 6 - 12 * 0.3, 1e-7);

  p.model->optimal_control->controls[0].polynomial = false;
  const OptimizeResult held = p.solve();
  ASSERT_TRUE(held.optimal) << held.status;
  EXPECT_NEAR(held.objective, 16.0, 1e-7);  // 12/(1 − 1/4): far from 12
}

// Radau of degree 1 has one point per interval: the polynomial is a constant, the problem the
// piecewise-constant one.
TEST(PolynomialControls, DegreeOneIsPiecewiseConstant) {
  testing::OptimalProblem p("data/double_integrator_polynomial.yaml");
  const OptimizeResult poly = p.solve(8, 1);
  p.model->optimal_control->controls[0].polynomial = false;
  const OptimizeResult held = p.solve(8, 1);
  ASSERT_TRUE(poly.optimal && held.optimal) << poly.status << "; " << held.status;
  EXPECT_NEAR(poly.objective, held.objective, 1e-9 * held.objective);
  ASSERT_EQ(poly.controls.size(), held.controls.size());
  for (size_t k = 0; k < held.controls.size(); ++k)
    EXPECT_NEAR(poly.controls[k], held.controls[k], 1e-6) << k;
}

// --verify's re-simulation follows the polynomials: from the optimum of the N = 2 problem the
// simulated state stays on the collocated one to the integrator's tolerance, while holding each
// interval's mean (the piecewise-constant reading) leaves it by O(h²).
TEST(PolynomialControls, ResimulationFollowsThePolynomials) {
  testing::OptimalProblem p("data/double_integrator_polynomial.yaml");
  const OptimizeResult r = p.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  SimulationOptions tight;
  tight.integrator.rtol = 1e-10;
  tight.integrator.atol = 1e-12;
  const VerifyResult v = verify(*p.dyn, p.spec(), r, tight);
  EXPECT_TRUE(v.message.empty()) << v.message;
  EXPECT_LT(v.largest_gap, 1e-8);
  EXPECT_LT(v.final_gap, 1e-8);
  OptimizeResult held = r;
  held.polynomial.assign(held.polynomial.size(), false);
  const VerifyResult off = verify(*p.dyn, p.spec(), held, tight);
  EXPECT_GT(off.final_gap, 1e-3);
}

// The exact Jacobian and Hessian with every non-constant control polynomial, on the problems the
// piecewise-constant checks use (test_transcription.cpp): a constrained model with a free horizon,
// a path constraint and a constant control beside the polynomial one among them.
class PolynomialDerivatives : public ::testing::TestWithParam<std::string> {};

TEST_P(PolynomialDerivatives, MatchCentralDifferences) {
  testing::OptimalProblem p(GetParam());
  make_polynomial(p);
  collocation::Transcription nlp(p.eq, p.cm, *p.dyn, p.spec(), 3, 3, p.cm->q0, p.cm->v0);
  const bool free = p.spec().free_horizon.has_value();
  testing::expect_first_derivatives_match(nlp, testing::perturbed_guess(nlp, free, 5));
  testing::expect_hessian_matches(nlp, testing::perturbed_guess(nlp, free, 13), 13);
}

INSTANTIATE_TEST_SUITE_P(Examples, PolynomialDerivatives,
                         ::testing::Values("double_integrator_min_time.yaml",
                                           "cart_pole_swing_up.yaml",
                                           "pendulum_swing_up_cartesian.yaml",
                                           "data/everything.yaml"),
                         [](const auto& info) {
                           std::string s = info.param.substr(0, info.param.size() - 5);
                           for (char& c : s)
                             if (c == '.' || c == '/') c = '_';
                           return s;
                         });

}  // namespace
}  // namespace lagrange
