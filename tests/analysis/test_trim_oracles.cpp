// docs/theory.md §5.5: trim against equilibria solved independently — a point-mass kite on a
// fixed line in a uniform wind, a tethered balloon's line in a uniform wind — and §4.5's drag
// ‖v‖v differentiable at v = 0.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "analysis/analysed.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {
namespace {

constexpr double kDegree = M_PI / 180.0;

size_t coordinate(const CompiledModel& cm, const std::string& name) {
  const auto it = std::find(cm.coordinate_names.begin(), cm.coordinate_names.end(), name);
  if (it == cm.coordinate_names.end()) throw std::invalid_argument("no coordinate " + name);
  return static_cast<size_t>(it - cm.coordinate_names.begin());
}

// examples/pointmass_kite.yaml: the AP2's mass (36.8 kg) and area (3 m²) on a rigid 200 m line
// (one segment: the point stays on the sphere |r| = L) in a uniform wind W = 20 m/s along x,
// C_L = 0.8, C_D = 0.6, roll 0, ρ = 1.225 kg/m³, the line's mass μL/2 lumped at the kite. At
// rest the apparent wind is −w: drag D = ½ρSW²C_D along x and lift L = ½ρSW²C_L along
// ê_D × ê_0 = x̂ × ŷ = ẑ (kite_aero.cpp). On the sphere, at elevation β and azimuth 0, the
// force (D, 0, L − m g) has no component along ê_β = (−sin β, 0, cos β):
//   tan β = (L − m g) / D.
TEST(TrimOracle, PointMassKiteOnAFixedLineBalancesLiftDragWeightAndTether) {
  auto s = testing::analyse_example("pointmass_kite.yaml");
  const double L = 200, W = 20, rho = 1.225, S = 3, q_area = rho * S * W * W / 2;
  const double lift = q_area * 0.8, drag = q_area * 0.6, mass = 36.8 + 0.0046 * L / 2;
  const double beta = std::atan2(lift - mass * 9.81, drag);  // ≈ 27.2°
  const CompiledModel& cm = *s.cm;
  const size_t x = coordinate(cm, "x"), y = coordinate(cm, "y"), z = coordinate(cm, "z");
  s.q[x] = L * std::cos(beta + 20 * kDegree);  // 20° above the balance
  s.q[y] = 0.0;
  s.q[z] = L * std::sin(beta + 20 * kDegree);
  s.v.assign(cm.nv, 0.0);
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  EXPECT_LE(r.residual, 1e-10);
  EXPECT_NEAR(r.q[x], L * std::cos(beta), 1e-9 * L);
  EXPECT_NEAR(r.q[y], 0.0, 1e-9 * L);
  EXPECT_NEAR(r.q[z], L * std::sin(beta), 1e-9 * L);
  EXPECT_NEAR(std::hypot(r.q[x], r.q[z]), L, 1e-9 * L);  // on the line
}

// A balloon (mass M, buoyancy B, drag k|v − w|(v − w)) on a rigid line of N segments with the
// simple drag model in a uniform wind U along x. At rest every segment's drag is
// f = ½ρ d (L/N) C_D U² along x whatever its direction (the drag acts on the whole apparent
// velocity), half to each end; each node weighs μL/(N + 1). Link j (nodes j − 1, j) carries what
// acts on the nodes above it, so it points along
//   F_j = (k U² + f (N − j) + f/2,  B − g (M + (N − j + 1) μL/(N + 1))),
// which the test checks node by node (the discrete catenary in wind). Trim starts from the
// straight line to (10, 0, 48); returns whether it took pseudo-transient continuation.
bool expect_static_shape(int N) {
  std::string yaml = R"(
name: tether in uniform wind
parameters: {M: 2.0, B: 60, g: 9.81, L: 50, mu: 0.0046, d: 0.002, U: 8, k: 0.6}
coordinates:
  x: {initial: 10}
  y: {initial: 0}
  z: {initial: 48}
points:
  balloon: [x, y, z]
particles:
  balloon: M
gravity: [0, 0, -g]
wind: {speed: U}
forces:
  - point: balloon
    force: [0, 0, B]
  - point: balloon
    force: -k*norm(vel(balloon) - [U, 0, 0])*(vel(balloon) - [U, 0, 0])
tethers:
  main: {between: [[0, 0, 0], balloon], segments: SEGMENTS, length: L, mass_per_length: mu,
         diameter: d, cd: 1.2, drag: simple}
)";
  yaml.replace(yaml.find("SEGMENTS"), 8, std::to_string(N));
  auto s = testing::analyse_string(yaml);
  const CompiledModel& cm = *s.cm;
  const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
  EXPECT_LE(r.residual, r.tolerance);
  // 1e-10, or the rounding floor of 50 light nodes 50 m out (6e-9; docs/theory.md §5.5)
  EXPECT_LE(r.tolerance, 1e-8);
  const double L = 50, U = 8, g = 9.81, mu = 0.0046, M = 2, B = 60, k = 0.6;
  const double f = 1.225 * 0.002 * (L / N) * 1.2 * U * U / 2, node = mu * L / (N + 1);
  const auto position = [&](int j) {
    if (j == 0) return Eigen::Vector3d::Zero().eval();
    const std::string p = j == N ? "" : "main.node" + std::to_string(j) + ".";
    return Eigen::Vector3d(r.q[coordinate(cm, p + "x")], r.q[coordinate(cm, p + "y")],
                           r.q[coordinate(cm, p + "z")]);
  };
  for (int j = 1; j <= N; ++j) {
    const Eigen::Vector3d link = position(j) - position(j - 1);
    EXPECT_NEAR(link.norm(), L / N, 1e-9) << "link " << j;
    const Eigen::Vector3d F(k * U * U + f * (N - j) + f / 2, 0.0, B - g * (M + (N - j + 1) * node));
    EXPECT_NEAR(link.normalized().cross(F.normalized()).norm(), 0.0, 1e-9) << "link " << j;
    EXPECT_GT(link.dot(F), 0.0) << "link " << j;  // in tension
  }
  // A simulation from the found state stays there (the balance is also stable: drag damps).
  SimulationOptions so;
  so.t_end = 2.0;
  so.output_step = 1.0;
  so.integrator.rtol = 1e-11;
  so.integrator.atol = 1e-12;
  const Trajectory tr = simulate(*s.dyn, so, r.q, r.v);
  EXPECT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  if (tr.status != Trajectory::Status::Complete) return r.pseudo_transient;
  const size_t width = tr.columns.size(), last = tr.data.size() / width - 1;
  for (size_t i = 0; i < cm.nq; ++i)
    EXPECT_NEAR(tr.data[last * width + 1 + i], r.q[i], 1e-7) << cm.coordinate_names[i];
  return r.pseudo_transient;
}

TEST(TrimOracle, TetherInAUniformWindReachesItsStaticShape) {
  (void)expect_static_shape(10);
}

// 50 segments from the straight line: Newton with a line search on ‖a‖ wandered off (the
// 50-segment balloon ended upwind of its anchor); Levenberg–Marquardt on the mass-weighted
// residual reaches the node-by-node balance without the continuation (docs/theory.md §5.5).
TEST(TrimOracle, FiftySegmentTetherTrimsFromTheStraightLine) {
  EXPECT_FALSE(expect_static_shape(50)) << "Levenberg–Marquardt needed the continuation";
}

// The drag −c‖v‖v has the derivative −c(‖v‖1 + v vᵀ/‖v‖), which is 0 at v = 0 but 0/0 on the
// tape as written. A line hanging at rest in still air: its linearisation must be finite and
// equal to the drag-free line's (quadratic drag adds no linear damping at rest).
TEST(TrimOracle, QuadraticDragIsDifferentiableAtRest) {
  const std::string chain = R"(
name: hanging line
parameters: {L: 10, mu: 0.05, d: 0.01}
gravity: [0, 0, -9.81]
tethers:
  line: {between: [[0, 0, 0], [8, 0, 0]], segments: 6, length: L, mass_per_length: mu,
         diameter: d, cd: 1.2, drag: DRAG}
)";
  const auto with = [&](const std::string& drag) {
    std::string text = chain;
    text.replace(text.find("DRAG"), 4, drag);
    auto s = testing::analyse_string(text);
    const TrimResult r = trim(*s.jac, *s.dyn, 0.0, s.q);
    return linearize(*s.jac, *s.dyn, 0.0, r.q.data(), r.v.data()).A;
  };
  const Eigen::MatrixXd plain = with("none"), simple = with("simple"), fine = with("fine");
  ASSERT_TRUE(simple.allFinite());
  ASSERT_TRUE(fine.allFinite());
  EXPECT_LE((simple - plain).cwiseAbs().maxCoeff(), 1e-8 * plain.cwiseAbs().maxCoeff());
  EXPECT_LE((fine - plain).cwiseAbs().maxCoeff(), 1e-8 * plain.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace lagrange
