// Elastic tethers (src/elements/tether_elastic.cpp, docs/theory.md §4.10): the static stretch of
// a hanging line against the heavy linear-elastic rope, the longitudinal modes of a taut line
// against the discrete chain's and the wave speed √(EA/μ), the energy balance with the elastic
// energy, the rigid limit EA → ∞, and slack segments that carry nothing.

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "analysis/analysed.hpp"
#include "elements/tether_models.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

constexpr double kM = 20, kGravity = 9.81, kL = 100, kLineDensity = 0.0046;
constexpr double kEA = 314159.0;  // E = 100 GPa, d = 2 mm (awebox's AP2 tether)

/// A load M on an elastic line of length L hung from the origin along −z.
std::string hanging_load(int segments, double ea, double damping, double z0, double zdot,
                         double xdot) {
  return fmt::format(R"(parameters: {{M: {}, g: {}, L: {}, mu: {}, EA: {}, D: {}}}
coordinates:
  x: {{initial: 0, rate: {}}}
  y: {{initial: 0}}
  z: {{initial: {}, rate: {}}}
points:
  load: [x, y, z]
particles:
  load: M
gravity: [0, 0, -g]
tethers:
  line:
    between: [[0, 0, 0], load]
    segments: {}
    length: L
    mass_per_length: mu
    elasticity: {{EA: EA, damping: D}}
)",
                     kM, kGravity, kL, kLineDensity, ea, damping, xdot, z0, zdot, segments);
}

/// The trajectory's first row from state (q, v): every output at that state.
Trajectory at_state(testing::Analysed& s, const std::vector<double>& q) {
  SimulationOptions so;
  so.t_end = 1e-9;
  so.output_step = 1e-9;
  return simulate(*s.dyn, so, q, std::vector<double>(q.size(), 0.0));
}

/// Trim with a tolerance on the accelerations for stiff lines: rounding in k/m ≈ 10⁶ s⁻² leaves
/// about 10⁻¹⁰ m/s²; 10⁻⁷ m/s² puts the nodes within 10⁻¹³ m of the equilibrium.
TrimResult stiff_trim(testing::Analysed& s, const std::vector<double>& q) {
  TrimOptions options;
  options.tol = 1e-7;
  return trim(*s.jac, *s.dyn, 0.0, q, options);
}

size_t coordinate(const testing::Analysed& s, const std::string& name) {
  const auto& n = s.cm->coordinate_names;
  return static_cast<size_t>(std::find(n.begin(), n.end(), name) - n.begin());
}

// A heavy linear-elastic rope of length L hung with a load M stretches by
// ΔL = g L (M + μL/2)/EA. The lumped line has it exactly: segment j carries
// g (M + (N − j + 1) μL/(N + 1)) and stretches by that times ℓ₀/EA, whose sum is the same.
TEST(ElasticTether, StaticStretchOfAHangingLineIsTheHeavyRopes) {
  for (int n : {3, 8}) {
    auto s = testing::analyse_string(hanging_load(n, kEA, 0, -kL - 0.01, 0, 0));
    const TrimResult r = stiff_trim(s, s.q);
    const double stretch = -r.q[coordinate(s, "z")] - kL;
    const double closed = kGravity * kL * (kM + kLineDensity * kL / 2) / kEA;
    EXPECT_NEAR(stretch, closed, 1e-9 * closed) << "N = " << n;
    const Trajectory tr = at_state(s, r.q);
    const double node_mass = kLineDensity * kL / (n + 1);
    for (int j = 1; j <= n; ++j) {
      const double tension = kGravity * (kM + (n - j + 1) * node_mass);
      EXPECT_NEAR(tr.at(0, fmt::format("line.tension_{}", j)), tension, 1e-8 * tension);
      EXPECT_NEAR(tr.at(0, fmt::format("line.strain_{}", j)), tension / kEA, 1e-9);
    }
    EXPECT_EQ(tr.at(0, "line.tension_ground"), tr.at(0, "line.tension_1"));
  }
}

// A line stretched between fixed ends without gravity: its longitudinal modes are the chain's,
// ω_k = 2 √(k/m) sin(kπ/2N) with k = EA/ℓ₀ and node mass m = μL/(N + 1), and ω₁ L/π approaches
// the wave speed √(EA/μ).
TEST(ElasticTether, LongitudinalModesAreTheChainsAndTravelAtTheWaveSpeed) {
  const int n = 20;
  const double span = kL * 1.01;
  auto s = testing::analyse_string(fmt::format(R"(parameters: {{L: {}, mu: {}, EA: {}}}
tethers:
  line:
    between: [[0, 0, 0], [{}, 0, 0]]
    segments: {}
    length: L
    mass_per_length: mu
    elasticity: {{EA: EA}}
)",
                                               kL, kLineDensity, kEA, span, n));
  const std::vector<Mode> all = modes(s.linear());
  const double k = kEA / (kL / n), m = kLineDensity * kL / (n + 1);
  for (int i = 1; i < n; ++i) {
    const double omega = 2 * std::sqrt(k / m) * std::sin(i * M_PI / (2 * n));
    double nearest = 1e300;
    for (const Mode& mode : all)
      nearest = std::min(nearest, std::abs(2 * M_PI * mode.frequency_hz - omega));
    EXPECT_LT(nearest, 1e-8 * omega) << "mode " << i;
  }
  const double omega1 = 2 * std::sqrt(k / m) * std::sin(M_PI / (2 * n));
  const double c = std::sqrt(kEA / kLineDensity);
  EXPECT_NEAR(omega1 * kL / M_PI, c, 0.03 * c);  // (N + 1)/N and the sine: about 2.5 %
}

// Without damping and drag the forces derive from U = Σ ½ EA ℓ₀ (ε⁺)²: kinetic + gravity +
// elastic energy stays constant through bounces in which segments go slack and taut again.
// The same run shows the slack segments carrying nothing.
class SlackLine : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto sys = testing::load_string(hanging_load(6, kEA, 0, -kL, 1.5, 3));
    SimulationOptions so = sys.options();
    so.t_end = 3;
    so.output_step = 0.002;
    so.integrator.rtol = 1e-11;
    so.integrator.atol = 1e-12;
    tr_ = new Trajectory(sys.run(so));
  }
  static void TearDownTestSuite() { delete tr_; }
  static Trajectory* tr_;
};
Trajectory* SlackLine::tr_ = nullptr;

TEST_F(SlackLine, KineticGravityAndElasticEnergyStayConstant) {
  const Trajectory& tr = *tr_;
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double e0 = tr.at(0, "energy") + tr.at(0, "line.elastic_energy");
  double worst = 0, most_elastic = 0;
  for (size_t r = 0; r < tr.rows(); ++r) {
    worst = std::max(worst, std::abs(tr.at(r, "energy") + tr.at(r, "line.elastic_energy") - e0));
    most_elastic = std::max(most_elastic, tr.at(r, "line.elastic_energy"));
  }
  EXPECT_GT(most_elastic, 10.0);  // the elastic energy takes part: J
  EXPECT_LT(worst, 1e-7 * std::abs(e0));
}

TEST_F(SlackLine, SlackSegmentsCarryNoCompression) {
  const Trajectory& tr = *tr_;
  size_t slack = 0, taut = 0;
  for (size_t r = 0; r < tr.rows(); ++r)
    for (int j = 1; j <= 6; ++j) {
      const double strain = tr.at(r, fmt::format("line.strain_{}", j));
      const double tension = tr.at(r, fmt::format("line.tension_{}", j));
      EXPECT_GE(tension, 0.0);
      if (strain < 0) {
        ++slack;
        EXPECT_EQ(tension, 0.0) << "t = " << tr.at(r, "t") << ", segment " << j;
      } else {
        ++taut;
        EXPECT_NEAR(tension, kEA * strain, 1e-9 * kEA * std::abs(strain) + 1e-9);
      }
    }
  EXPECT_GT(slack, 100u);  // the line does go slack
  EXPECT_GT(taut, 100u);
}

// Damping pulls only while taut: a slack segment being stretched fast carries nothing (to the
// rounding of the branch-free max: ε and |ε| are evaluated in different sums).
TEST(ElasticTether, DampedSlackSegmentsCarryNothing) {
  auto sys = testing::load_string(hanging_load(6, kEA, 3000, -kL + 1, 0, 0));
  SimulationOptions so = sys.options();
  so.t_end = 1;
  so.output_step = 0.001;
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  size_t slack = 0;
  for (size_t r = 0; r < tr.rows(); ++r)
    for (int j = 1; j <= 6; ++j) {
      EXPECT_GE(tr.at(r, fmt::format("line.tension_{}", j)), -1e-12 * kEA);
      if (tr.at(r, fmt::format("line.strain_{}", j)) < 0) {
        ++slack;
        EXPECT_LT(std::abs(tr.at(r, fmt::format("line.tension_{}", j))), 1e-12 * kEA);
      }
    }
  EXPECT_GT(slack, 10u);
}

// The seed's winch (examples/winch.yaml) with an elastic line: its free drum unreels the hanging
// line. The segments' pull on the reeled-out length, Q_ℓ (docs/theory.md §4.10), is what turns
// the drum: without damping the total energy (drum, line, gravity, elastic) stays constant, and a
// stiff line follows the rigid line's ℓ(t) = ℓ(0) cosh(ωt), ω² = μ g R²/(J + μ L R²), to within
// its strain (≈ 2·10⁻³).
TEST(ElasticTether, AFreeDrumUnreelsAnElasticLineAsARigidOneAndKeepsTheEnergy) {
  auto sys = testing::load_string(R"(parameters: {R: 0.2, J: 0.05, mu: 0.4, L: 30, g: 9.81}
gravity: [0, 0, -g]
winches:
  drum:
    tether: line
    radius: R
    inertia: J
    total_length: L
    initial: {reeled_out: 1, rate: 0}
tethers:
  line:
    between: [[0, 0, 0], free]
    segments: 5
    mass_per_length: mu
    elasticity: {EA: 1.0e4}
)");
  SimulationOptions so = sys.options();
  so.t_end = 1.5;
  so.output_step = 0.01;
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  const Trajectory tr = sys.run(so);
  ASSERT_EQ(tr.status, Trajectory::Status::Complete) << tr.message;
  const double e0 = tr.at(0, "energy") + tr.at(0, "line.elastic_energy");
  double worst = 0;
  for (size_t r = 0; r < tr.rows(); ++r)
    worst = std::max(worst, std::abs(tr.at(r, "energy") + tr.at(r, "line.elastic_energy") - e0));
  EXPECT_LT(worst, 1e-7 * std::max(1.0, std::abs(e0)));
  const double omega = std::sqrt(0.4 * 9.81 * 0.04 / (0.05 + 0.4 * 30 * 0.04));
  const size_t last = tr.rows() - 1;
  const double rigid = std::cosh(omega * tr.at(last, "t"));
  EXPECT_NEAR(tr.at(last, "drum.reeled_out"), rigid, 1e-3 * rigid);  // measured: 5·10⁻⁵
  EXPECT_GT(tr.at(last, "drum.reeled_out"), 1.3);                    // it did unreel
}

/// The hanging chain of tether_models.hpp made elastic with stiffness EA.
std::string elastic_chain(int segments, double ea) {
  return testing::hanging_chain(segments) + fmt::format("    elasticity: {{EA: {}}}\n", ea);
}

// As EA grows the elastic chain's static shape and support tension approach the rigid chain's,
// the difference falling as 1/EA.
TEST(ElasticTether, StiffLimitIsTheRigidChain) {
  const int n = 6;
  auto rigid = testing::analyse_string(testing::hanging_chain(n));
  const TrimResult rr = trim(*rigid.jac, *rigid.dyn, 0.0, rigid.q);
  const double t_rigid = at_state(rigid, rr.q).at(0, "chain.tension_ground");
  double previous = 0;
  for (double ea : {1e4, 1e6}) {
    auto s = testing::analyse_string(elastic_chain(n, ea));
    // From the rigid shape sagged 1 % deeper: every segment taut, off the kink at ε = 0.
    std::vector<double> q0(s.q.size());
    for (size_t i = 0; i < q0.size(); ++i) {
      const std::string& name = s.cm->coordinate_names[i];
      q0[i] = rr.q[coordinate(rigid, name)] * (name.back() == 'z' ? 1.01 : 1.0);
    }
    const TrimResult r = stiff_trim(s, q0);
    double shape = 0;
    for (size_t i = 0; i < r.q.size(); ++i)
      shape =
          std::max(shape, std::abs(r.q[i] - rr.q[coordinate(rigid, s.cm->coordinate_names[i])]));
    const double tension = at_state(s, r.q).at(0, "chain.tension_ground");
    const double err = std::abs(tension - t_rigid) / t_rigid;
    EXPECT_LT(shape, 1e3 / ea) << "EA = " << ea;
    if (previous > 0) {
      EXPECT_NEAR(previous / err, 100, 5) << "EA = " << ea;
    }
    previous = err;
  }
  EXPECT_LT(previous, 1e-4);
}

}  // namespace
}  // namespace lagrange
