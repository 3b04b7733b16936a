// Tethers (src/elements/tether.cpp): the hanging chain against the catenary, tension outputs,
// the static balance in wind, dissipation by drag and the energy balance with drag and wind.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

#include "elements/tether_models.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

constexpr double kSpan = 8, kLength = 10, kMu = 0.5, kG = 9.81;

/// The catenary z = a cosh((x − span/2)/a) − a cosh(span/(2a)) through both supports with
/// arc length L: 2a sinh(span/(2a)) = L, solved by bisection.
double catenary_parameter() {
  double lo = 0.1, hi = 100;
  for (int i = 0; i < 200; ++i) {
    const double a = (lo + hi) / 2;
    (2 * a * std::sinh(kSpan / (2 * a)) > kLength ? lo : hi) = a;
  }
  return (lo + hi) / 2;
}

/// Settled chain: simulate 20 s with damping, return the last row.
Trajectory settle(int segments, const std::string& model) {
  auto sys = testing::load_string(testing::hanging_chain(segments, model));
  SimulationOptions so = sys.options();
  so.t_end = 20;
  so.output_step = 1;
  Trajectory tr = sys.run(so);
  EXPECT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  return tr;
}

double catenary_error(const Trajectory& tr, int segments) {
  const double a = catenary_parameter();
  const size_t last = tr.rows() - 1;
  double err = 0;
  for (int j = 1; j < segments; ++j) {
    const double x = tr.at(last, fmt::format("chain.node{}.x", j));
    const double z = tr.at(last, fmt::format("chain.node{}.z", j));
    const double zc = a * std::cosh((x - kSpan / 2) / a) - a * std::cosh(kSpan / (2 * a));
    err = std::max(err, std::abs(z - zc));
  }
  return err;
}

TEST(HangingChain, ConvergesToTheCatenaryAsOneOverNSquared) {
  double previous = 0;
  for (int n : {5, 10, 20}) {
    const Trajectory tr = settle(n, "lumped");
    const size_t last = tr.rows() - 1;
    EXPECT_LT(std::abs(tr.at(last, "kinetic")), 1e-12) << "not at rest, N = " << n;
    const double err = catenary_error(tr, n);
    if (previous > 0) {
      EXPECT_GT(previous / err, 3.0) << "N = " << n << ": " << previous << " -> " << err;
      EXPECT_LT(previous / err, 5.5) << "N = " << n << ": " << previous << " -> " << err;
    }
    previous = err;
  }
  EXPECT_LT(previous, 5e-3);  // N = 20
}

TEST(HangingChain, LumpedAndFullModelsHangInTheSameShape) {
  const Trajectory lumped = settle(10, "lumped"), full = settle(10, "full");
  for (int j = 1; j < 10; ++j)
    for (const char* c : {"x", "z"}) {
      const std::string col = fmt::format("chain.node{}.{}", j, c);
      EXPECT_NEAR(lumped.at(lumped.rows() - 1, col), full.at(full.rows() - 1, col), 1e-8) << col;
    }
}

// The support's tension in newtons (λ ℓ/N): its vertical part carries half the weight resting on
// the chain exactly, and it approaches the catenary's μ g a cosh(span/(2a)). In the seed's lumped
// model each of the N + 1 nodes has μℓ/(N + 1), and the shares at the two fixed supports do not
// load the chain, so the interior carries (N − 1)/(N + 1) of the weight.
TEST(HangingChain, SupportTensionBalancesTheWeightInNewtons) {
  const int n = 20;
  const Trajectory tr = settle(n, "lumped");
  const size_t last = tr.rows() - 1;
  const double tension = tr.at(last, "chain.tension_ground");
  const double sine = -tr.at(last, "chain.node1.z") / (kLength / n);
  const double carried = (n - 1) * kMu * kLength * kG / (n + 1);
  EXPECT_NEAR(tension * sine, carried / 2, 1e-8 * carried);
  const double a = catenary_parameter();
  const double catenary = kMu * kG * a * std::cosh(kSpan / (2 * a));
  EXPECT_NEAR(tension, catenary, 2.0 / (n + 1) * catenary);
  EXPECT_DOUBLE_EQ(tension, tr.at(last, "chain.tension_1"));
  EXPECT_NEAR(tr.at(last, "chain.tension_1"), tr.at(last, "chain.tension_20"), 1e-8 * tension);
  EXPECT_DOUBLE_EQ(tr.at(last, "chain.length"), kLength);
  EXPECT_DOUBLE_EQ(tr.at(last, "chain.mass"), kMu * kLength);
}

// A tether from the origin to a free end with a 3 kg point mass, in a uniform wind of 10 m/s
// along x with simple drag: at rest, every node's forces are constant (weight, half the drag of
// each neighbouring segment), so segment j points along the sum of the forces at nodes j … N.
// The static shape is built from that sum, independently of the engine.
TEST(TetherInWind, SteadyStateMatchesTheStaticForceBalance) {
  const int n = 8;
  const double L = 20, mu = 0.05, d = 0.01, cd = 1.2, rho = 1.225, U = 10, M = 3, g = 9.81;
  const std::string yaml = fmt::format(R"(parameters: {{M: {}, g: {}}}
coordinates:
  x: {{initial: 5}}
  y: {{initial: 0}}
  z: {{initial: -19}}
points:
  load: [x, y, z]
particles:
  load: M
gravity: [0, 0, -g]
wind: {{profile: uniform, speed: {}, direction: [1, 0, 0]}}
tethers:
  line:
    between: [[0, 0, 0], load]
    segments: {}
    length: {}
    mass_per_length: {}
    diameter: {}
    cd: {}
    air_density: {}
    drag: simple
    damping: 0.5
forces:
  - {{point: load, force: -5*vel(load)}}
)",
                                       M, g, U, n, L, mu, d, cd, rho);
  auto sys = testing::load_string(yaml);
  SimulationOptions so = sys.options();
  so.t_end = 60;
  so.output_step = 1;
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const size_t last = tr.rows() - 1;
  ASSERT_LT(tr.at(last, "kinetic"), 1e-12);

  const double s = L / n, node_mass = mu * L / (n + 1);
  const double drag = 0.5 * rho * d * s * cd * U * U;  // per segment, along +x
  std::vector<std::array<double, 3>> force(n + 1);
  for (int j = 1; j <= n; ++j)
    force[j] = {drag * ((j == n) ? 0.5 : 1.0), 0, -node_mass * g - (j == n ? M * g : 0)};
  // Segment j points along Σ_{i ≥ j} Fᵢ from node j − 1 to node j; march from the anchor.
  std::array<double, 3> sum{0, 0, 0}, r{0, 0, 0};
  std::vector<std::array<double, 3>> dir(n + 1);
  for (int j = n; j >= 1; --j) {
    for (int k = 0; k < 3; ++k) sum[k] += force[j][k];
    const double norm = std::sqrt(sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]);
    EXPECT_NEAR(tr.at(last, fmt::format("line.tension_{}", j)), norm, 1e-7 * norm);
    for (int k = 0; k < 3; ++k) dir[j][k] = sum[k] / norm;
  }
  for (int j = 1; j <= n; ++j) {
    for (int k = 0; k < 3; ++k) r[k] += s * dir[j][k];
    const std::string node = j == n ? "" : fmt::format("line.node{}.", j);
    EXPECT_NEAR(tr.at(last, j == n ? "x" : node + "x"), r[0], 1e-6) << "node " << j;
    EXPECT_NEAR(tr.at(last, j == n ? "z" : node + "z"), r[2], 1e-6) << "node " << j;
  }
}

std::string swinging_tether(const std::string& drag, const std::string& wind) {
  return fmt::format(R"(parameters: {{g: 9.81}}
gravity: [0, 0, -g]
{}
tethers:
  rope:
    between: [[0, 0, 10], free]
    segments: 6
    length: 6
    mass_per_length: 0.3
    diameter: 0.02
    drag: {}
)",
                     wind, drag);
}

/// Starts a hanging rope with a sideways velocity on every node.
Trajectory swing(const std::string& yaml, double t_end) {
  auto sys = testing::load_string(yaml);
  std::vector<double> v0 = sys.compiled->v0;
  for (size_t i = 0; i < sys.compiled->nv; ++i)
    if (sys.compiled->velocity_names[i].find(".x_dot") != std::string::npos) v0[i] = 2.0;
  SimulationOptions so = testing::tight(sys, t_end, 0.001);
  return simulate(*sys.dynamics, so, sys.compiled->q0, v0);
}

TEST(TetherDrag, InStillAirEnergyOnlyDecreases) {
  const Trajectory tr = swing(swinging_tether("simple", ""), 3);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  for (size_t r = 1; r < tr.rows(); ++r)
    ASSERT_LE(tr.at(r, "energy"), tr.at(r - 1, "energy") + 1e-9) << "t = " << tr.at(r, "t");
  EXPECT_LT(tr.at(tr.rows() - 1, "energy"), tr.at(0, "energy") - 0.1);
}

// d(T + U)/dt = P_drag: the trapezoidal integral of the drag power (column rope.drag_power)
// matches the energy change, for both drag models, in still air and in a gusty sheared wind.
TEST(TetherDrag, EnergyChangeEqualsIntegratedDragPower) {
  const std::string gusty =
      "wind: {profile: power_law, speed: 6, reference_height: 10, exponent: 0.14, "
      "direction: [1, 0, 0], gust: 1 + 0.3*sin(2*t)}";
  for (const char* drag : {"simple", "fine"})
    for (const std::string& wind : {std::string(), gusty}) {
      const Trajectory tr = swing(swinging_tether(drag, wind), 2);
      ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
      double work = 0, flow = 0;
      for (size_t r = 1; r < tr.rows(); ++r) {
        const double dt = tr.at(r, "t") - tr.at(r - 1, "t");
        const double p0 = tr.at(r - 1, "rope.drag_power"), p1 = tr.at(r, "rope.drag_power");
        work += dt * (p0 + p1) / 2;
        flow += dt * (std::abs(p0) + std::abs(p1)) / 2;
      }
      const double change = tr.at(tr.rows() - 1, "energy") - tr.at(0, "energy");
      EXPECT_NEAR(change, work, 1e-5 * flow) << drag << " drag, wind: " << wind;
      EXPECT_GT(flow, 0.1);
    }
}

// Reel-out at constant speed: ℓ(t) and the airborne mass μℓ(t) exactly as prescribed; the
// segments stretch with ℓ (N is fixed), so the tension has no jumps.
TEST(TetherReelOut, FollowsThePrescribedLengthWithSmoothTension) {
  auto sys = testing::load_example("tether_reel_out.yaml");
  const Trajectory tr = sys.run(sys.options());
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  double max_jump = 0, max_tension = 0;
  for (size_t r = 0; r < tr.rows(); ++r) {
    const double t = tr.at(r, "t");
    EXPECT_NEAR(tr.at(r, "line.length"), 5 + 0.5 * t, 1e-12);
    EXPECT_NEAR(tr.at(r, "line.mass"), 0.05 * (5 + 0.5 * t), 1e-12);
    if (r > 0)
      max_jump = std::max(max_jump, std::abs(tr.at(r, "line.tension_ground") -
                                             tr.at(r - 1, "line.tension_ground")));
    max_tension = std::max(max_tension, std::abs(tr.at(r, "line.tension_ground")));
  }
  EXPECT_GT(max_tension, 5.0);
  EXPECT_LT(max_jump, 0.03 * max_tension);  // per 0.01 s sample
}

}  // namespace
}  // namespace lagrange
