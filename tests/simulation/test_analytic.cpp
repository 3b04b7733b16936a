// Simulations against closed-form solutions and conservation laws.

#include <gtest/gtest.h>

#include <cmath>

#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::load_example;
using testing::load_string;

// Complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean.
double elliptic_K(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double an = (a + b) / 2;
    b = std::sqrt(a * b);
    a = an;
  }
  return M_PI / (2 * a);
}

const char* kOscillator = R"(
name: harmonic oscillator
parameters: {m: 2.0, k: 50.0}
coordinates:
  x: {initial: 0.3, rate: 0.7}
points:
  anchor: [0, 0, 0]
  body: [x, 0, 0]
particles: {body: m}
potential: k/2*x^2
simulate: {t_end: 10, output_step: 0.05}
)";

TEST(Analytic, HarmonicOscillatorClosedForm) {
  auto sys = load_string(kOscillator);
  for (const char* method : {"arkode", "cvode"}) {
    SimulationOptions so = sys.options();
    so.integrator.method = method;
    so.integrator.rtol = 1e-12;
    so.integrator.atol = 1e-14;
    const Trajectory tr = sys.run(so);
    ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
    const double w = std::sqrt(50.0 / 2.0);
    double worst = 0;
    for (size_t r = 0; r < tr.rows(); ++r) {
      const double t = tr.at(r, "t");
      const double exact = 0.3 * std::cos(w * t) + 0.7 / w * std::sin(w * t);
      worst = std::max(worst, std::abs(tr.at(r, "x") - exact));
    }
    EXPECT_LT(worst, 1e-8) << method;
    EXPECT_DOUBLE_EQ(tr.at(tr.rows() - 1, "t"), 10.0);
  }
}

// θ zero crossings located by cubic Hermite interpolation of (θ, θ̇) between samples.
std::vector<double> zero_crossings(const Trajectory& tr, const std::string& q) {
  std::vector<double> out;
  const std::string qd = q + "_dot";
  for (size_t r = 0; r + 1 < tr.rows(); ++r) {
    const double t0 = tr.at(r, "t"), t1 = tr.at(r + 1, "t"), h = t1 - t0;
    const double y0 = tr.at(r, q), y1 = tr.at(r + 1, q);
    if ((y0 < 0) == (y1 < 0)) continue;
    const double d0 = tr.at(r, qd) * h, d1 = tr.at(r + 1, qd) * h;
    auto H = [&](double s) {
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * y0 + (s3 - 2 * s2 + s) * d0 + (-2 * s3 + 3 * s2) * y1 +
             (s3 - s2) * d1;
    };
    double lo = 0, hi = 1;
    for (int i = 0; i < 80; ++i) {
      const double mid = (lo + hi) / 2;
      ((H(lo) < 0) == (H(mid) < 0) ? lo : hi) = mid;
    }
    out.push_back(t0 + h * (lo + hi) / 2);
  }
  return out;
}

TEST(Analytic, LargeAmplitudePendulumPeriod) {
  auto sys = load_example("pendulum.yaml");
  const SimulationOptions so = testing::tight(sys, sys.model->simulate.t_end, 0.002);
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const auto z = zero_crossings(tr, "theta");
  ASSERT_GE(z.size(), 3u);
  const double g = 9.81, l = 1.0, theta0 = 2.5;
  const double expected = 4 * std::sqrt(l / g) * elliptic_K(std::sin(theta0 / 2));
  const double measured = z[2] - z[0];
  EXPECT_NEAR(measured / expected, 1.0, 1e-8) << measured << " vs " << expected;
}

TEST(Analytic, DoublePendulumConservesEnergy) {
  auto sys = load_example("double_pendulum.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 20;
  so.integrator.rtol = 1e-11;
  so.integrator.atol = 1e-13;
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double e0 = tr.at(0, "energy");
  double drift = 0;
  for (size_t r = 0; r < tr.rows(); ++r) drift = std::max(drift, std::abs(tr.at(r, "energy") - e0));
  EXPECT_LT(drift / std::abs(e0), 1e-8);
  // The chaotic motion really happened: the lower link went over the top.
  double max_theta2 = 0;
  for (size_t r = 0; r < tr.rows(); ++r)
    max_theta2 = std::max(max_theta2, std::abs(tr.at(r, "theta2")));
  EXPECT_GT(max_theta2, 3.0);
}

TEST(Analytic, Rk4ConvergesAtFourthOrder) {
  auto sys = load_example("double_pendulum.yaml");
  SimulationOptions ref = sys.options();
  ref.t_end = 1;
  ref.output_step = 0.1;
  ref.integrator.rtol = 1e-13;
  ref.integrator.atol = 1e-15;
  const std::vector<double> q0{0.4, -0.3}, v0{0.0, 0.5};  // regular (non-chaotic) regime
  const Trajectory exact = simulate(*sys.dynamics, ref, q0, v0);
  auto error_with_step = [&](double h) {
    SimulationOptions so = ref;
    so.integrator.method = "rk4";
    so.integrator.step = h;
    const Trajectory tr = simulate(*sys.dynamics, so, q0, v0);
    const size_t last = tr.rows() - 1;
    return std::hypot(tr.at(last, "theta1") - exact.at(last, "theta1"),
                      tr.at(last, "theta2") - exact.at(last, "theta2"));
  };
  const double e1 = error_with_step(0.05), e2 = error_with_step(0.025),
               e3 = error_with_step(0.0125);
  EXPECT_NEAR(std::log2(e1 / e2), 4.0, 0.3) << e1 << " " << e2;
  EXPECT_NEAR(std::log2(e2 / e3), 4.0, 0.3) << e2 << " " << e3;
}

TEST(Analytic, DamperDissipatesAndSpringSettles) {
  auto sys = load_example("spring_mass_damper.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 60;
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  // Energy never increases; the mass settles at the static equilibrium y = −(l0 + m g / k).
  for (size_t r = 1; r < tr.rows(); ++r)
    EXPECT_LE(tr.at(r, "energy"), tr.at(r - 1, "energy") + 1e-9) << r;
  EXPECT_NEAR(tr.at(tr.rows() - 1, "y"), -(1.0 + 9.81 / 100.0), 1e-6);
}

TEST(Analytic, ParametersChangeWithoutNewDerivation) {
  auto sys = load_example("pendulum.yaml");
  SimulationOptions so = sys.options();
  so.t_end = 1;
  const Trajectory a = sys.run(so);
  std::vector<double> p = sys.compiled->parameter_defaults;
  p[static_cast<size_t>(sys.model->parameter_index("l"))] = 4.0;  // period doubles
  sys.dynamics->set_parameters(p);
  SimulationOptions so2 = so;
  so2.t_end = 2;
  const Trajectory b = sys.run(so2);
  EXPECT_NEAR(b.at(b.rows() - 1, "theta"), a.at(a.rows() - 1, "theta"), 1e-6);
}

}  // namespace
}  // namespace lagrange
