// Rigid bodies in SO(3) (docs/theory.md §4.4): conservation laws of a free body, the
// intermediate-axis flip, orthonormality drift with and without the correction Ξ, a compound
// pendulum in SO(3) against the same bar posed by one angle, and a heavy top against Euler angles.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "simulation/body_models.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

using testing::load_model;
using testing::omega_at;
using testing::rotation_at;
using testing::tight;

TEST(RigidBody, CsvColumnsOfAFreeBody) {
  auto sys = load_model(testing::free_brick(2, 3, 4, {0, 1, 0}));
  const auto& cols = trajectory_columns(*sys.compiled);
  for (const char* c :
       {"brick.x", "brick.y", "brick.z", "brick.R11", "brick.R23", "brick.R33", "brick.vx",
        "brick.wx", "brick.wy", "brick.wz", "brick.orthonormality_error"})
    EXPECT_NE(std::find(cols.begin(), cols.end(), c), cols.end()) << c;
  EXPECT_EQ(sys.compiled->nq, 12u);
  EXPECT_EQ(sys.compiled->nv, 6u);
  EXPECT_EQ(sys.compiled->parameter_names.back(), "stabilization.gamma");
}

// Torque-free body: T and the world-frame angular momentum R I ω are first integrals.
TEST(RigidBody, FreeBodyConservesEnergyAndWorldAngularMomentum) {
  const Eigen::Vector3d I(2, 3, 4);
  auto sys = load_model(testing::free_brick(I[0], I[1], I[2], {0.3, 5.0, 0.2}));
  const Trajectory tr = sys.run(tight(sys, 100, 0.1));
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double T0 = tr.at(0, "kinetic");
  const Eigen::Vector3d L0 =
      rotation_at(tr, 0, "brick") * I.asDiagonal() * omega_at(tr, 0, "brick");
  double worst_T = 0, worst_L = 0;
  for (size_t r = 0; r < tr.rows(); ++r) {
    worst_T = std::max(worst_T, std::abs(tr.at(r, "kinetic") - T0) / T0);
    const Eigen::Vector3d L =
        rotation_at(tr, r, "brick") * I.asDiagonal() * omega_at(tr, r, "brick");
    worst_L = std::max(worst_L, (L - L0).norm() / L0.norm());
  }
  RecordProperty("energy_relative_drift", fmt::format("{:.3e}", worst_T));
  RecordProperty("momentum_relative_drift", fmt::format("{:.3e}", worst_L));
  EXPECT_LT(worst_T, 1e-9);
  EXPECT_LT(worst_L, 1e-9);
}

// Dzhanibekov: a spin about the intermediate axis flips; spins about the major and minor
// axes stay close to where they started.
TEST(RigidBody, IntermediateAxisFlipsMajorAndMinorDoNot) {
  auto spin_sign_changes = [](int axis) {
    std::array<double, 3> w0{0.01, 0.01, 0.01};
    w0[static_cast<size_t>(axis)] = 5.0;
    auto sys = load_model(testing::free_brick(2, 3, 4, w0));
    const Trajectory tr = sys.run(tight(sys, 40, 0.05));
    EXPECT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
    const std::string col = std::string("brick.w") + "xyz"[axis];
    double min_ratio = 1;
    int flips = 0;
    for (size_t r = 1; r < tr.rows(); ++r) {
      if ((tr.at(r, col) > 0) != (tr.at(r - 1, col) > 0)) ++flips;
      min_ratio = std::min(min_ratio, tr.at(r, col) / 5.0);
    }
    return std::make_pair(flips, min_ratio);
  };
  const auto minor = spin_sign_changes(0), middle = spin_sign_changes(1),
             major = spin_sign_changes(2);
  EXPECT_GE(middle.first, 2);
  EXPECT_LT(middle.second, -0.9);
  EXPECT_EQ(minor.first, 0);
  EXPECT_GT(minor.second, 0.99);
  EXPECT_EQ(major.first, 0);
  EXPECT_GT(major.second, 0.99);
}

std::vector<double> orthonormality_errors(testing::Loaded& sys, double gamma,
                                          const SimulationOptions& so) {
  std::vector<double> p = sys.compiled->parameter_defaults;
  p.back() = gamma;  // stabilization.gamma, a runtime parameter
  sys.dynamics->set_parameters(p);
  const Trajectory tr = sys.run(so);
  EXPECT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  std::vector<double> e;
  for (size_t r = 0; r < tr.rows(); ++r) e.push_back(tr.at(r, "brick.orthonormality_error"));
  return e;
}

// docs/theory.md §4.4: Ξ = (γ/2)((RᵀR)⁻¹ − 1) makes RᵀR − 1 decay like exp(−γ t), so R stays
// orthonormal; without it the integrator's error accumulates.
TEST(RigidBody, OrthonormalityCorrectionKeepsRInSO3) {
  auto sys = load_model(testing::free_brick(2, 3, 4, {0.3, 5.0, 0.2}));
  SimulationOptions so = tight(sys, 1000, 0.5);
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  const std::vector<double> with = orthonormality_errors(sys, 10.0, so);
  const double worst = *std::max_element(with.begin(), with.end());
  RecordProperty("orthonormality_1000s_gamma10", fmt::format("{:.3e}", worst));
  EXPECT_LT(worst, 1e-10);

  SimulationOptions loose = tight(sys, 100, 10);
  loose.integrator.rtol = 1e-5;
  loose.integrator.atol = 1e-7;
  loose.project = false;  // Ξ alone, without the re-orthonormalisation at output samples
  const std::vector<double> without = orthonormality_errors(sys, 0.0, loose);
  const std::vector<double> corrected = orthonormality_errors(sys, 1.0, loose);
  RecordProperty("orthonormality_loose_gamma0", fmt::format("{:.3e}", without.back()));
  RecordProperty("orthonormality_loose_gamma1", fmt::format("{:.3e}", corrected.back()));
  EXPECT_GT(without.back(), 5 * without[1]);  // grows with time
  EXPECT_GT(without.back(), 1e-5);
  EXPECT_GT(without.back(), 5 * corrected.back());
}

// The pivot C(r, R) = r + R p = 0 in SO(3) against the bar posed by one angle.
TEST(RigidBody, CompoundPendulumSO3MatchesPlanarAndPivotReaction) {
  const double th0 = 1.0, w0 = 0.5;
  auto so3 = load_model(testing::compound_pendulum_so3(th0, w0));
  auto planar = load_model(testing::compound_pendulum_planar(th0, w0));
  const SimulationOptions so = tight(so3, 10, 0.01);
  const Trajectory a = so3.run(so);
  const Trajectory b = planar.run(so);
  ASSERT_EQ(a.status, Trajectory::Status::Complete) << a.message;
  ASSERT_EQ(b.status, Trajectory::Status::Complete) << b.message;
  ASSERT_EQ(a.rows(), b.rows());
  const double m = 2.0, l = 1.0, g = 9.81;
  const double Izz = m * (1.0 / 400 + l * l) / 12, Ip = Izz + m * l * l / 4;
  double worst = 0, worst_force = 0;
  for (size_t r = 0; r < a.rows(); ++r) {
    const double th = b.at(r, "theta"), thd = b.at(r, "theta_dot");
    const double th_so3 = std::atan2(a.at(r, "bar.R21"), a.at(r, "bar.R11"));
    worst = std::max({worst, std::abs(std::remainder(th_so3 - th, 2 * M_PI)),
                      std::abs(a.at(r, "bar.wz") - thd)});
    // Force of the pivot on the bar: m(a_c − g) with a_c = (l/2)(θ̈ t̂ − θ̇² ê), ê from the
    // pivot to the centre of mass; the multipliers are its negative (L = T − U − λᵀC).
    const double thdd = -m * g * l / 2 * std::sin(th) / Ip;
    const Eigen::Vector2d e(std::sin(th), -std::cos(th)), tang(std::cos(th), std::sin(th));
    const Eigen::Vector2d ac = l / 2 * (thdd * tang - thd * thd * e);
    const Eigen::Vector2d F = m * (ac - Eigen::Vector2d(0, -g));
    const Eigen::Vector2d lambda(a.at(r, "pivot_x"), a.at(r, "pivot_y"));
    worst_force = std::max(worst_force, (lambda + F).norm());
    // Along the bar: tension m(g cos θ + (l/2) θ̇²) pulls the bar towards the pivot.
    EXPECT_NEAR(-lambda.dot(-e), m * (g * std::cos(th) + l / 2 * thd * thd), 1e-6);
  }
  RecordProperty("so3_vs_planar", fmt::format("{:.3e}", worst));
  RecordProperty("pivot_force_error", fmt::format("{:.3e}", worst_force));
  EXPECT_LT(worst, 1e-7);
  EXPECT_LT(worst_force, 1e-6);
}

TEST(RigidBody, HeavyTopMatchesEulerAnglesAndPrecessesAtTheFastTopRate) {
  testing::TopSetup s;
  auto so3 = load_model(testing::heavy_top_so3(s));
  auto euler = load_model(testing::heavy_top_euler(s));
  const SimulationOptions so = tight(so3, 5, 0.01);
  const Trajectory a = so3.run(so);
  const Trajectory b = euler.run(so);
  ASSERT_EQ(a.status, Trajectory::Status::Complete) << a.message;
  ASSERT_EQ(b.status, Trajectory::Status::Complete) << b.message;
  double worst = 0;
  for (size_t r = 0; r < a.rows(); ++r) {
    const double ph = b.at(r, "phi"), th = b.at(r, "theta");
    const Eigen::Vector3d axis_euler(std::sin(ph) * std::sin(th), -std::cos(ph) * std::sin(th),
                                     std::cos(th));
    const Eigen::Vector3d axis_so3 = rotation_at(a, r, "top").col(2);
    worst = std::max(worst, (axis_so3 - axis_euler).norm());
  }
  RecordProperty("top_so3_vs_euler", fmt::format("{:.3e}", worst));
  EXPECT_LT(worst, 1e-6);
  // Mean precession rate of the symmetry axis over the run against m g d / (I₃ ω₃).
  const size_t last = a.rows() - 1;
  auto azimuth = [&](size_t r) {
    const Eigen::Vector3d z = rotation_at(a, r, "top").col(2);
    return std::atan2(z[0], -z[1]);
  };
  double total = 0;
  for (size_t r = 1; r <= last; ++r) total += std::remainder(azimuth(r) - azimuth(r - 1), 2 * M_PI);
  const double rate = total / (a.at(last, "t") - a.at(0, "t"));
  const double predicted = s.m * s.g * s.d / (s.i3 * s.psid);
  RecordProperty("precession_rate", fmt::format("{:.3e}", rate));
  EXPECT_NEAR(rate, predicted, 0.01 * predicted);
}

}  // namespace
}  // namespace lagrange
