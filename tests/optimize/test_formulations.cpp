// Optimal control against known optima and a second formulation: the pendulum swing-up in
// Cartesian coordinates with its rod against the polar angle, the LQ problem against the
// sampled-data Riccati solution, and the cart-pole's cost converging as N doubles.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <fstream>
#include <string>
#include <unsupported/Eigen/MatrixFunctions>

#include "lagrange/io.hpp"
#include "optimal_problem.hpp"

namespace lagrange {
namespace {

// The same swing-up in two formulations (examples/optimal/pendulum_swing_up_{polar,cartesian}):
// the same optimal cost at the same N and degree, the Cartesian one on its rod along the whole
// trajectory, and its final y = 1, y_dot = 0 reached though they were implied, not imposed.
TEST(OptimalFormulations, CartesianSwingUpHasThePolarCost) {
  testing::OptimalProblem polar("pendulum_swing_up_polar.yaml"),
      cartesian("pendulum_swing_up_cartesian.yaml");
  const OptimizeResult p = polar.solve(), c = cartesian.solve();
  ASSERT_TRUE(p.optimal) << p.status;
  ASSERT_TRUE(c.optimal) << c.status;
  EXPECT_NEAR(c.objective, p.objective, 1e-4 * p.objective);
  // The collocation drifts off the rod between the imposed start and the end, by its
  // discretisation error: about 16 times less as N doubles (4.1e-3 at N = 15, 2.4e-4 at 30).
  const auto drift = [](const Trajectory& traj) {
    const size_t x = traj.column_index("x"), y = traj.column_index("y"), cols = traj.columns.size();
    double most = 0.0;
    for (size_t r = 0; r < traj.rows(); ++r) {
      const double* row = traj.data.data() + r * cols;
      most = std::max(most, std::fabs(row[x] * row[x] + row[y] * row[y] - 1.0) / 2);
    }
    return most;
  };
  const OptimizeResult coarse = cartesian.solve(15, 3);
  ASSERT_TRUE(coarse.optimal) << coarse.status;
  EXPECT_LT(drift(c.trajectory), 1e-3);
  EXPECT_LT(drift(c.trajectory), drift(coarse.trajectory) / 8);
  // y(T) = 1 was implied, not imposed: reached to the drift.
  const Trajectory& traj = c.trajectory;
  const double* last = traj.data.data() + (traj.rows() - 1) * traj.columns.size();
  EXPECT_NEAR(last[traj.column_index("y")], 1.0, 1e-4);
  EXPECT_NE(c.worst_constraint.find("implied"), std::string::npos) << c.worst_constraint;
  // The polar optimum's force at the mesh points is the Cartesian one's (the same problem).
  ASSERT_EQ(p.controls.size(), c.controls.size());
  for (size_t k = 0; k < p.controls.size(); ++k)
    EXPECT_NEAR(c.controls[k], p.controls[k], 2e-2 * (1 + std::fabs(p.controls[k]))) << k;
}

// A final value that the constraints imply is checked: one that cannot be reached is reported as
// such, by name, with exit status not optimal (here y = 0.5 with x = 0 is off the rod).
TEST(OptimalFormulations, AnUnreachableImpliedFinalValueIsNamed) {
  testing::OptimalProblem cartesian("pendulum_swing_up_cartesian.yaml");
  OptimalControlSpec& spec = *cartesian.model->optimal_control;
  for (BoundaryValue& b : spec.final)
    if (!b.state.velocity && b.state.coordinate == 1) b.bounds.lower = b.bounds.upper = 0.5;
  const OptimizeResult r = cartesian.solve(10, 3);
  EXPECT_FALSE(r.optimal);
  EXPECT_NE(r.worst_constraint.find("final value of 'y' (implied by the constraints)"),
            std::string::npos)
      << r.worst_constraint;
  EXPECT_GT(r.violation, 0.4);
  EXPECT_NE(r.status.find("another branch of the constraints"), std::string::npos) << r.status;
}

// docs/theory.md §10: with u constant on each interval, the LQ problem is the sampled-data one:
// x_{k+1} = A_d x_k + B_d u_k, cost Σ z_kᵀ W_d z_k + x_Nᵀ P_T x_N with z = (x, u), from Van
// Loan's exponential of [[−Fᵀ, W], [0, F]] h, F = [[A, B], [0, 0]]. Its optimum x₀ᵀ P₀ x₀ comes
// from the backward Riccati recursion; collocation at degree 5 matches it to O(h⁹).
TEST(OptimalFormulations, LinearQuadraticMatchesTheSampledDataRiccatiSolution) {
  testing::OptimalProblem lq("data/lq_spring.yaml");
  const OptimizeResult r = lq.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  const double m = 1.0, k = 4.0, c = 0.4, T = 3.0;
  const int N = 30;
  const double h = T / N;
  Eigen::Matrix3d F = Eigen::Matrix3d::Zero(), W = Eigen::Matrix3d::Zero();
  F << 0, 1, 0, -k / m, -c / m, 1 / m, 0, 0, 0;
  W.diagonal() << 1.0, 0.5, 1.0;  // x² + 0.5 x'² + u² = zᵀ W z
  Eigen::Matrix<double, 6, 6> big = Eigen::Matrix<double, 6, 6>::Zero();
  big.topLeftCorner<3, 3>() = -F.transpose();
  big.topRightCorner<3, 3>() = W;
  big.bottomRightCorner<3, 3>() = F;
  const Eigen::Matrix<double, 6, 6> E = (big * h).exp();
  const Eigen::Matrix3d Phi = E.bottomRightCorner<3, 3>();
  const Eigen::Matrix3d Wd = Phi.transpose() * E.topRightCorner<3, 3>();
  const Eigen::Matrix2d A = Phi.topLeftCorner<2, 2>();
  const Eigen::Vector2d B = Phi.topRightCorner<2, 1>();
  const Eigen::Matrix2d Q = Wd.topLeftCorner<2, 2>();
  const Eigen::Vector2d S = Wd.topRightCorner<2, 1>();
  const double R = Wd(2, 2);
  Eigen::Matrix2d P;
  P << 2.0, 0.0, 0.0, 1.0;  // the terminal term 2x² + x'²
  for (int i = 0; i < N; ++i) {
    const double Huu = R + B.dot(P * B);
    const Eigen::RowVector2d Hux = S.transpose() + B.transpose() * P * A;
    P = Q + A.transpose() * P * A - Hux.transpose() * Hux / Huu;
  }
  const Eigen::Vector2d x0(1.0, 0.0);
  const double J = x0.dot(P * x0);
  EXPECT_NEAR(r.objective, J, 1e-6 * J) << "Riccati " << J;
  // Not the continuous-time optimum: the piecewise-constant control costs more.
  EXPECT_GT(r.objective, 0.0);
}

// Kelly (2017)'s cart-pole swing-up: with u constant per interval the cost converges at second
// order, so successive differences shrink by about 4 as N doubles.
TEST(OptimalFormulations, CartPoleCostConvergesAtSecondOrder) {
  testing::OptimalProblem cp("cart_pole_swing_up.yaml");
  const OptimizeResult a = cp.solve(25, 3), b = cp.solve(50, 3), c = cp.solve(100, 3);
  ASSERT_TRUE(a.optimal && b.optimal && c.optimal) << a.status << b.status << c.status;
  const double ratio = (a.objective - b.objective) / (b.objective - c.objective);
  EXPECT_GT(ratio, 3.0) << a.objective << " " << b.objective << " " << c.objective;
  EXPECT_LT(ratio, 5.5) << a.objective << " " << b.objective << " " << c.objective;
}

// guess: FILE.csv starts from an earlier solution: the same optimum from a coarser mesh's solution
// and from the same mesh's, which needs fewer iterations than the default guess (only the primal
// point is warm: Ipopt's barrier starts again from its own μ).
TEST(OptimalFormulations, AnEarlierSolutionWarmStartsTheSolve) {
  testing::OptimalProblem cp("cart_pole_swing_up.yaml");
  const OptimizeResult coarse = cp.solve(20, 3), cold = cp.solve(40, 3);
  ASSERT_TRUE(coarse.optimal && cold.optimal) << coarse.status << cold.status;
  const std::string dir = ::testing::TempDir();
  write_trajectory_csv(coarse.trajectory, dir + "coarse.csv");
  write_trajectory_csv(cold.trajectory, dir + "same.csv");
  OptimalControlSpec& spec = *cp.model->optimal_control;
  spec.guess_file = dir + "coarse.csv";
  const OptimizeResult warm = cp.solve(40, 3);
  spec.guess_file = dir + "same.csv";
  const OptimizeResult again = cp.solve(40, 3);
  ASSERT_TRUE(warm.optimal && again.optimal) << warm.status << again.status;
  EXPECT_NEAR(warm.objective, cold.objective, 1e-8 * cold.objective);
  EXPECT_NEAR(again.objective, cold.objective, 1e-8 * cold.objective);
  EXPECT_LT(again.iterations, cold.iterations);
  // A file without the model's columns is refused, naming the column.
  std::ofstream(dir + "bad.csv") << "t,x\n0,0\n1,1\n";
  spec.guess_file = dir + "bad.csv";
  try {
    cp.solve(10, 3);
    FAIL() << "a guess file without theta was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("has no column"), std::string::npos) << e.what();
  }
}

// A periodic problem with a free period and nothing to optimise finds the Van der Pol limit cycle
// (μ = 1): its period 6.6632868593 (Andersen and Geer 1982), converging at the collocation's
// order 2d − 1 = 5.
TEST(OptimalFormulations, VanDerPolPeriodIsTheKnownValue) {
  testing::OptimalProblem vdp("van_der_pol_limit_cycle.yaml");
  const double period = 6.6632868593;
  const OptimizeResult coarse = vdp.solve(40, 3), fine = vdp.solve(80, 3);
  ASSERT_TRUE(coarse.optimal && fine.optimal) << coarse.status << fine.status;
  EXPECT_NEAR(coarse.horizon, period, 2e-5);
  EXPECT_LT(std::fabs(fine.horizon - period), std::fabs(coarse.horizon - period) / 8);
}

// The same on a constrained model: the Cartesian pendulum's free oscillation, whose period is
// 4 K(sin(θ₀/2)) √(l/g) (K by the arithmetic–geometric mean), with y and its rate on the rod.
TEST(OptimalFormulations, CartesianPendulumPeriodIsTheEllipticIntegral) {
  testing::OptimalProblem pendulum("data/pendulum_period_cartesian.yaml");
  const double k = std::sin(0.5);
  double a = 1.0, b = std::sqrt(1 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double next = (a + b) / 2;
    b = std::sqrt(a * b);
    a = next;
  }
  const double period = 4 * (M_PI / (2 * a)) * std::sqrt(1.0 / 9.81);
  const OptimizeResult coarse = pendulum.solve(30, 3), fine = pendulum.solve(60, 3);
  ASSERT_TRUE(coarse.optimal && fine.optimal) << coarse.status << fine.status;
  EXPECT_NEAR(coarse.horizon, period, 2e-6);
  EXPECT_LT(std::fabs(fine.horizon - period), std::fabs(coarse.horizon - period) / 16);
  // The orbit closes: x(T) = x(0) imposed, y(T) = y(0) on the rod.
  const Trajectory& traj = fine.trajectory;
  const size_t y = traj.column_index("y"), cols = traj.columns.size();
  EXPECT_NEAR(traj.data[(traj.rows() - 1) * cols + y], traj.data[y], 1e-6);
}

}  // namespace
}  // namespace lagrange
