// docs/theory.md §5.5, steady states: rates held, the other velocities 0, a = 0. The oracle is
// the heavy symmetric top's steady precession, written in Euler angles (φ precession, θ
// nutation, ψ spin, pivot at the origin, centre of mass at distance l on the symmetry axis):
//
//   L = ½ I₁ (θ̇² + φ̇² sin²θ) + ½ I₃ (ψ̇ + φ̇ cos θ)² − m g l cos θ.
//
// φ and ψ are cyclic. The θ equation, I₁ θ̈ = I₁ φ̇² sin θ cos θ − I₃ ω₃ φ̇ sin θ + m g l sin θ with
// ω₃ = ψ̇ + φ̇ cos θ, with θ̇ = θ̈ = 0, φ̇ = Ω, ψ̇ = s and sin θ ≠ 0 gives
//
//   (I₁ − I₃) Ω² cos θ − I₃ s Ω + m g l = 0,
//
// so cos θ = (I₃ s Ω − m g l) / ((I₁ − I₃) Ω²) for given rates, and for a given θ the slow
// precession is the root Ω = (I₃ s − √(I₃² s² − 4 (I₁ − I₃) cos θ m g l)) / (2 (I₁ − I₃) cos θ).

#include <gtest/gtest.h>

#include <cmath>

#include "analysis/analysed.hpp"
#include "analysis/euler_top.hpp"

namespace lagrange {
namespace {

constexpr double kM = 1.0, kG = 9.81, kL = 0.1, kI1 = 0.006, kI3 = 0.01, kSpin = 20.0;

const char* const kTop = testing::kEulerTop;

TEST(SteadyState, TopFindsTheNutationAngleOfSteadyPrecession) {
  auto s = testing::analyse_string(kTop);
  TrimOptions options;
  options.steady = {true, false, true};  // φ̇ and ψ̇ held; θ the only position varied
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q, s.v, options);
  const double Omega = 4.55;
  const double expected =
      std::acos((kI3 * kSpin * Omega - kM * kG * kL) / ((kI1 - kI3) * Omega * Omega));
  EXPECT_NEAR(r.q[1], expected, 1e-9);
  EXPECT_NE(std::abs(r.q[1] - 0.8), 0.0);  // it moved from 0.8 (expected ≈ 0.541)
  EXPECT_EQ(r.v[0], Omega);                // held exactly
  EXPECT_EQ(r.v[1], 0.0);
  EXPECT_EQ(r.v[2], kSpin);
  EXPECT_EQ(r.q[0], 0.0);  // the cyclic coordinates are the phase of the motion: not varied
  EXPECT_EQ(r.q[2], 0.0);
  EXPECT_LE(r.residual, 1e-10);
  EXPECT_EQ(r.drift, 0.0);  // φ, ψ do not enter the accelerations: steady, not quasi-steady
}

TEST(SteadyState, TopFindsThePrecessionRateAtAGivenAngle) {
  auto s = testing::analyse_string(kTop);
  const double theta = 0.5;
  s.set("theta", theta);
  TrimOptions options;
  options.steady = {true, false, true};
  options.free = {false, false, false};
  options.free_rates = {true, false, false};  // Ω varied from 4.55, θ and s held
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q, s.v, options);
  const double a = (kI1 - kI3) * std::cos(theta), b = -kI3 * kSpin, c = kM * kG * kL;
  const double slow = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  EXPECT_NEAR(r.v[0], slow, 1e-9);
  EXPECT_EQ(r.q[1], theta);
  EXPECT_EQ(r.v[2], kSpin);
  EXPECT_LE(r.residual, 1e-10);
  // The simulation from the found state keeps θ: steady precession, not nutation.
  std::vector<double> qdot(3), acc(3), lambda;
  s.dyn->forward(0.0, r.q.data(), r.v.data(), qdot.data(), acc.data(), lambda.data());
  EXPECT_LE(std::abs(acc[1]), 1e-10);
}

// A mass on a spring, moving at a held rate: a(x) = −k x/m depends on the moving coordinate, so
// the state x = 0 found is only quasi-steady, and the drift says by how much (|ȧ| = k v/m).
TEST(SteadyState, DriftOfAHeldRateThatMovesTheDynamics) {
  auto s = testing::analyse_string(R"(
name: spring
parameters: {m: 2.0, k: 8.0}
coordinates:
  x: {initial: 0.3, rate: 0.5}
  y: {initial: 0.2, rate: 0}
kinetic: m/2*(der(x)^2 + der(y)^2)
potential: k/2*(x^2 + (y - x)^2)
)");
  TrimOptions options;
  options.steady = {true, false};
  options.free = {true, true};  // x varied too: it is where the motion passes through a = 0
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q, s.v, options);
  EXPECT_NEAR(r.q[0], 0.0, 1e-10);
  EXPECT_NEAR(r.q[1], 0.0, 1e-10);
  // ȧ = ∂a/∂q v: ȧ_x = −(2k/m) v, ȧ_y = (k/m) v.
  EXPECT_NEAR(r.drift, 2 * 8.0 / 2.0 * 0.5, 1e-12);
}

TEST(SteadyState, AFreeBodysRateCannotBeHeld) {
  auto s = testing::analyse_example("heavy_top.yaml");
  TrimOptions options;
  options.steady.assign(s.cm->nv, false);
  options.steady.back() = true;  // ω₃
  try {
    (void)trim(*s.jac, *s.dyn, 0.0, s.q, s.v, options);
    FAIL() << "a free body's spin was held";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("free body"), std::string::npos) << e.what();
  }
  options.steady.assign(s.cm->nv, false);
  options.free_rates.assign(s.cm->nv, false);
  options.free_rates[0] = true;
  EXPECT_THROW((void)trim(*s.jac, *s.dyn, 0.0, s.q, s.v, options), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange
