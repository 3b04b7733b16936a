// Free bodies in an optimal-control problem (docs/theory.md §10, "Free bodies"): the state keeps
// R ∈ SO(3) with its drift term, RᵀR = 1 is imposed once at t = 0 where the fixed values leave R
// free, and periodicity is imposed on the components the invariant leaves independent.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "optimize/optimal_problem.hpp"
#include "optimize/transcription.hpp"

namespace lagrange {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Column `name` of the trajectory's row `row`.
double at(const Trajectory& t, size_t row, const std::string& name) {
  const auto it = std::find(t.columns.begin(), t.columns.end(), name);
  EXPECT_NE(it, t.columns.end()) << name;
  return t.data[row * t.columns.size() + static_cast<size_t>(it - t.columns.begin())];
}

// A quarter turn at rest to rest with isotropic inertia J: the fixed-axis rotation on the
// double-integrator schedule, J_N = 12 J² θ² / (T³ (1 − 1/N²)) for piecewise-constant torques
// (the discrete minimum-energy problem, exact in the torque; the collocated R' = R Ω only errs
// in the final orientation, at the collocation's order). Refining N approaches 12 J² θ²/T³.
TEST(FreeBodies, AttitudeSlewMatchesTheDoubleIntegratorClosedForm) {
  testing::OptimalProblem slew("attitude_slew.yaml");
  const double J = 2.0, theta = kPi / 2, T = 2.0;
  for (const int N : {10, 20}) {
    const OptimizeResult r = slew.solve(N);
    ASSERT_TRUE(r.optimal) << r.status;
    const double n2 = static_cast<double>(N * N);
    const double expected = 12 * J * J * theta * theta / (T * T * T * (1 - 1 / n2));
    EXPECT_NEAR(r.objective, expected, 1e-5 * expected) << "N = " << N;
    // About z only: the other torques vanish, and the body ends at rest turned by θ.
    for (size_t k = 0; k < static_cast<size_t>(N); ++k) {
      EXPECT_NEAR(r.controls[3 * k], 0.0, 1e-6);
      EXPECT_NEAR(r.controls[3 * k + 1], 0.0, 1e-6);
    }
    const size_t last = r.trajectory.rows() - 1;
    // R21 is implied by the imposed entries and RᵀR = 1, which the collocated kinematics keep to
    // their accuracy (4.5e-7 at N = 10).
    EXPECT_NEAR(at(r.trajectory, last, "sat.R21"), 1.0, 2e-6);
    EXPECT_NEAR(at(r.trajectory, last, "sat.wz"), 0.0, 1e-9);
    // Halfway the body has turned by θ/2 about z, on SO(3).
    const size_t mid = (r.trajectory.rows() - 1) / 2;
    EXPECT_NEAR(at(r.trajectory, mid, "t"), T / 2, 1e-12);
    EXPECT_NEAR(std::atan2(at(r.trajectory, mid, "sat.R21"), at(r.trajectory, mid, "sat.R11")),
                theta / 2, 1e-6);
    EXPECT_NEAR(at(r.trajectory, mid, "sat.R33"), 1.0, 1e-9);
  }
}

// The final orientation fixes nine entries of which RᵀR = 1 implies six: three are imposed, the
// rest checked; nothing is imposed at t = 0, where every value is fixed.
TEST(FreeBodies, FinalOrientationImposesOnlyItsIndependentEntries) {
  testing::OptimalProblem slew("attitude_slew.yaml");
  collocation::Transcription nlp(slew.eq, slew.cm, *slew.dyn, slew.spec(), 10, 3, slew.cm->q0,
                                 slew.cm->v0, HessianChoice::LimitedMemory);
  EXPECT_EQ(nlp.start_invariant_rows(), 0u);
  const std::vector<double> x = nlp.guess();
  // The guess turns about z between the boundary orientations (on SO(3), not a straight line).
  const double* mid = nlp.state(x.data(), 5, 0);
  const size_t R = 3;  // sat.x, .y, .z, then R11 …
  EXPECT_NEAR(mid[R + 0], std::cos(kPi / 4), 1e-12);
  EXPECT_NEAR(mid[R + 3], std::sin(kPi / 4), 1e-12);
  EXPECT_EQ(nlp.implied_final_gaps(x.data()).size(), 6u);
}

// A periodic spin with its orientation free at t = 0 but for R21: the torque-free spin at 2π rad/s
// about the vertical closes in T = 1 s, so J = 0 at R(0) = 1; R(T) = R(0) holds in all nine entries
// though only three are imposed (the other six to the drift of RᵀR at T, the collocation's
// error: 2.6e-6 at N = 20), and R(0) is orthonormal.
TEST(FreeBodies, PeriodicSpinClosesOnSO3WithRImposedOnce) {
  testing::OptimalProblem spin("data/spin_orbit.yaml");
  collocation::Transcription nlp(spin.eq, spin.cm, *spin.dyn, spin.spec(), 20, 3, spin.cm->q0,
                                 spin.cm->v0, HessianChoice::LimitedMemory);
  const size_t nx = spin.cm->nq + spin.cm->nv;  // 12 + 6
  EXPECT_EQ(nlp.start_invariant_rows(), 6u);    // RᵀR = 1 at t = 0 (R21 = 0 is one of R's 3)
  EXPECT_EQ(nlp.periodic_rows(), 12u);          // r, ṙ, ω and three entries of R
  EXPECT_LE(nlp.periodic_rows() + nlp.start_invariant_rows(), nx);

  const OptimizeResult r = spin.solve();
  ASSERT_TRUE(r.optimal) << r.status;
  EXPECT_LT(r.objective, 1e-8);
  const Trajectory& t = r.trajectory;
  const size_t last = t.rows() - 1;
  double gram[3][3] = {};
  for (const char* e : {"R11", "R12", "R13", "R21", "R22", "R23", "R31", "R32", "R33"}) {
    const std::string name = std::string("top.") + e;
    EXPECT_NEAR(at(t, last, name), at(t, 0, name), 1e-5) << name;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a)
        gram[i][j] += at(t, 0, fmt::format("top.R{}{}", a + 1, i + 1)) *
                      at(t, 0, fmt::format("top.R{}{}", a + 1, j + 1));
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(gram[i][j], i == j ? 1.0 : 0.0, 1e-9);
      EXPECT_NEAR(at(t, 0, fmt::format("top.R{}{}", i + 1, j + 1)), i == j ? 1.0 : 0.0, 1e-6);
    }
  EXPECT_NEAR(at(t, 0, "top.wz"), 2 * kPi, 1e-12);
}

}  // namespace
}  // namespace lagrange
