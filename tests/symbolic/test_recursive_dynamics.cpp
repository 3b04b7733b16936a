// The recursive formulation (docs/theory.md §4.9) against two independent references: the
// Lagrangian formulation of the same model (every example with a joint tree and both URDF arms),
// and the closed-form mass matrix of the planar point-mass pendulum in absolute angles for chains
// of up to 200 links. Also: energies, linear size, and the reasons it does not apply.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <filesystem>
#include <random>

#include "support/test_paths.hpp"
#include "n_link_pendulum.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

/// A model compiled in one formulation, evaluated at states.
struct Formulated {
  std::shared_ptr<const CompiledModel> compiled;
  std::unique_ptr<Dynamics> dynamics;
  size_t definitions = 0;
  Formulated(const Model& model, Formulation form) {
    const Equations eq = derive(model, form);
    definitions = eq.definitions.size();
    compiled = compile(eq);
    dynamics = std::make_unique<Dynamics>(compiled, compiled->parameter_defaults);
  }
  std::vector<double> accelerations(double t, const std::vector<double>& q,
                                    const std::vector<double>& v) {
    std::vector<double> qdot(q.size()), a(v.size());
    dynamics->forward(t, q.data(), v.data(), qdot.data(), a.data(), nullptr);
    return a;
  }
  std::vector<double> observables(double t, const std::vector<double>& q,
                                  const std::vector<double>& v) {
    std::vector<double> out(compiled->observables.num_outputs());
    dynamics->observe(t, q.data(), v.data(), out.data());
    return out;
  }
};

double max_abs(const std::vector<double>& x) {
  double m = 0;
  for (double e : x) m = std::max(m, std::abs(e));
  return m;
}

/// The largest |a_r − a_l| over random states, relative to max(1, ‖a_l‖∞); likewise T and U.
void expect_same_dynamics(const Model& model, const std::string& label) {
  Formulated lagrangian(model, Formulation::Lagrangian), recursive(model, Formulation::Recursive);
  const size_t n = lagrangian.compiled->nv;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int s = 0; s < 6; ++s) {
    std::vector<double> q(n), v(n);
    for (size_t i = 0; i < n; ++i) {
      q[i] = u(rng);
      v[i] = u(rng);
    }
    const double t = 0.25 * s;
    const auto al = lagrangian.accelerations(t, q, v), ar = recursive.accelerations(t, q, v);
    const double scale = std::max(1.0, max_abs(al));
    for (size_t i = 0; i < n; ++i)
      EXPECT_LE(std::abs(ar[i] - al[i]), 1e-12 * scale) << label << " state " << s << " a" << i;
    const auto ol = lagrangian.observables(t, q, v), orr = recursive.observables(t, q, v);
    for (size_t k = 0; k < ol.size(); ++k)
      EXPECT_LE(std::abs(orr[k] - ol[k]), 1e-12 * std::max(1.0, std::abs(ol[k])))
          << label << " state " << s << " observable " << k;
  }
}

TEST(RecursiveDynamics, AgreesWithLagrangianOnEveryExampleWithAJointTree) {
  size_t tried = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(LAGRANGE_SOURCE_DIR) + "/examples")) {
    if (entry.path().extension() != ".yaml") continue;
    const Model model = read_model_file(entry.path().string());
    if (!recursive_unsuitable(model).empty()) continue;
    expect_same_dynamics(model, entry.path().filename().string());
    ++tried;
  }
  EXPECT_GE(tried, 3u);  // elbow manipulator, planar arm under PD control, two-link arm
}

// A spatial tree with every kind of joint and every force the recursive form takes as a joint
// force: two branches from one base, axes off the frame axes, rpy origins, a prismatic and
// a fixed joint; a spring, a damper, a point force, a written potential, joint torques.
TEST(RecursiveDynamics, AgreesWithLagrangianOnASpatialTreeWithForces) {
  const std::string yaml = R"(
name: spatial tree
parameters: {g: 9.81, k: 30, c: 0.4}
links:
  base:
    joint: {name: q1, type: revolute, axis: [0, 0, 1], initial: 0.3}
    mass: 0.5
    com: [0, 0.02, 0.05]
    inertia: [0.003, 0.003, 0.001]
  arm:
    parent: base
    joint: {name: q2, type: revolute, axis: [1, 2, 2], origin: {xyz: [0.1, 0, 0.3], rpy: [0.2, -0.4, 0.7]}, initial: -0.5, rate: 0.4}
    mass: 1.3
    com: [0.2, 0.05, -0.1]
    inertia: [[0.02, 0.001, -0.002], [0.001, 0.03, 0.004], [-0.002, 0.004, 0.025]]
  slider:
    parent: arm
    joint: {name: q3, type: prismatic, axis: [0, 1, 1], origin: {xyz: [0.4, 0, 0], rpy: [0, 0.3, 0]}, initial: 0.1, torque: -2*q3}
    mass: 0.7
    com: [0, 0.02, 0.03]
    inertia: [0.004, 0.005, 0.006]
    points: {tip: [0, 0.3, 0]}
  hand:
    parent: slider
    joint: {type: fixed, origin: {xyz: [0, 0.3, 0], rpy: [0.5, 0, 0]}}
    mass: 0.2
    com: [0.05, 0, 0]
    inertia: [0.001, 0.001, 0.002]
  other:
    parent: base
    joint: {name: q4, type: revolute, axis: [0, 1, 0], origin: {xyz: [-0.2, 0, 0.1]}, initial: 1.0, damping: 0.3}
    mass: 0.9
    com: [0, 0, -0.3]
    inertia: [0.01, 0.01, 0.002]
    points: {end: [0, 0, -0.6]}
points:
  anchor: [0.5, 0.5, 0.5]
springs:
  - {between: [anchor, slider.tip], k: k, l0: 0.2}
dampers:
  - {between: [anchor, other.end], c: c}
forces:
  - {point: other.end, force: [sin(t), 0, 1]}
potential: 0.5*q1^2
gravity: [0, 0, -g]
)";
  const Model model = read_model_string(yaml, "<spatial tree>");
  ASSERT_EQ(recursive_unsuitable(model), "");
  expect_same_dynamics(model, "spatial tree");
}

TEST(RecursiveDynamics, AgreesWithLagrangianOnTheUrdfArms) {
  for (const char* arm : {"ur5.urdf", "panda.urdf"}) {
    const Model model =
        read_model_file(std::string(LAGRANGE_SOURCE_DIR) + "/examples/robots/" + arm);
    ASSERT_EQ(recursive_unsuitable(model), "") << arm;
    expect_same_dynamics(model, arm);
  }
}

TEST(RecursiveDynamics, PivotsAreTheLeafFirstEliminationOfTheMassMatrix) {
  // docs/theory.md §4.9, Pivots: D_i is M_ii − M_iT M_TT⁻¹ M_Ti with T the joints beyond i (the
  // Schur complement left when they are eliminated first), so all D_i > 0 ⇔ M > 0.
  for (const char* file : {"robots/ur5.urdf", "elbow_manipulator.yaml"}) {
    SCOPED_TRACE(file);
    const Model model = read_model_file(std::string(LAGRANGE_SOURCE_DIR) + "/examples/" + file);
    const Equations rec = derive(model, Formulation::Recursive);
    const Equations lag = derive(model, Formulation::Lagrangian);
    const size_t n = lag.nv;
    ASSERT_EQ(rec.pivots.size(), n);
    std::vector<GiNaC::ex> entries;
    for (size_t i = 0; i < n; ++i)
      for (size_t j = 0; j < n; ++j)
        entries.push_back(lag.M(static_cast<unsigned>(i), static_cast<unsigned>(j)));
    const Tape mass = Tape::compile(entries, lag.tape_inputs());
    const Tape pivots = Tape::compile(rec.pivots, rec.tape_inputs(), rec.definitions);
    // The joints beyond each coordinate's joint, from the tree (parents before children).
    std::vector<std::vector<size_t>> beyond(n);
    for (size_t k = 0; k < model.tree.size(); ++k)
      for (int a = model.tree[k].parent; a >= 0; a = model.tree[static_cast<size_t>(a)].parent)
        if (model.tree[static_cast<size_t>(a)].coordinate >= 0 && model.tree[k].coordinate >= 0)
          beyond[static_cast<size_t>(model.tree[static_cast<size_t>(a)].coordinate)].push_back(
              static_cast<size_t>(model.tree[k].coordinate));
    Formulated at(model, Formulation::Lagrangian);
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-2, 2);
    for (int s = 0; s < 4; ++s) {
      std::vector<double> q(n), v(n);
      for (size_t i = 0; i < n; ++i) {
        q[i] = u(rng);
        v[i] = u(rng);
      }
      (void)at.accelerations(0.0, q, v);
      const std::vector<double>& in = at.dynamics->last_inputs();
      std::vector<double> Mv(n * n), D(n), work(std::max(mass.work_size(), pivots.work_size()));
      mass.eval(in.data(), Mv.data(), work.data());
      pivots.eval(in.data(), D.data(), work.data());
      const Eigen::MatrixXd M =
          Eigen::Map<const Eigen::MatrixXd>(Mv.data(), static_cast<long>(n), static_cast<long>(n));
      for (size_t i = 0; i < n; ++i) {
        const auto& T = beyond[i];
        double schur = M(static_cast<long>(i), static_cast<long>(i));
        if (!T.empty()) {
          const long m = static_cast<long>(T.size());
          Eigen::MatrixXd MTT(m, m);
          Eigen::VectorXd MTi(m);
          for (long a = 0; a < m; ++a) {
            MTi[a] = M(static_cast<long>(T[static_cast<size_t>(a)]), static_cast<long>(i));
            for (long b = 0; b < m; ++b)
              MTT(a, b) = M(static_cast<long>(T[static_cast<size_t>(a)]),
                            static_cast<long>(T[static_cast<size_t>(b)]));
          }
          schur -= MTi.dot(MTT.ldlt().solve(MTi));
        }
        EXPECT_GT(D[i], 0.0) << i;
        EXPECT_NEAR(D[i], schur, 1e-10 * M.diagonal().cwiseAbs().maxCoeff()) << "pivot " << i;
      }
    }
  }
}

// Planar point masses m_k on massless links l_k, absolute angles φ: M_ij = S_ij l_i l_j cos(φ_i −
// φ_j), h_i = −l_i Σ_j S_ij l_j sin(φ_i − φ_j) φ̇_j² − g l_i sin φ_i S_ii, S_ij = Σ_{k ≥ max(i,j)}
// m_k; solved in long double. With φ_k = q_1 + … + q_k the joint accelerations are differences.
std::vector<double> closed_form_chain(const std::vector<double>& q, const std::vector<double>& v) {
  using LD = long double;
  const size_t n = q.size();
  std::vector<LD> phi(n), w(n), tail(n + 1, 0), l(n);
  LD p = 0, r = 0;
  for (size_t k = 0; k < n; ++k) {
    p += q[k];
    r += v[k];
    phi[k] = p;
    w[k] = r;
    l[k] = bench::per_link_length(k + 1);
  }
  for (size_t k = n; k-- > 0;) tail[k] = tail[k + 1] + bench::per_link_mass(k + 1);
  Eigen::Matrix<LD, Eigen::Dynamic, Eigen::Dynamic> M(n, n);
  Eigen::Matrix<LD, Eigen::Dynamic, 1> h(n);
  for (size_t i = 0; i < n; ++i) {
    h[static_cast<long>(i)] = -9.81L * l[i] * std::sin(phi[i]) * tail[i];
    for (size_t j = 0; j < n; ++j) {
      const LD s = tail[std::max(i, j)] * l[i] * l[j];
      M(static_cast<long>(i), static_cast<long>(j)) = s * std::cos(phi[i] - phi[j]);
      h[static_cast<long>(i)] -= s * std::sin(phi[i] - phi[j]) * w[j] * w[j];
    }
  }
  const Eigen::Matrix<LD, Eigen::Dynamic, 1> phidd = M.llt().solve(h);
  std::vector<double> a(n);
  for (size_t k = 0; k < n; ++k)
    a[k] = static_cast<double>(phidd[static_cast<long>(k)] -
                               (k > 0 ? phidd[static_cast<long>(k) - 1] : 0.0L));
  return a;
}

class RecursiveChain : public ::testing::TestWithParam<size_t> {};

TEST_P(RecursiveChain, MatchesTheClosedFormPendulum) {
  const size_t n = GetParam();
  const Model model = read_model_string(bench::links_chain_yaml(n), "<chain>");
  Formulated recursive(model, Formulation::Recursive);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int s = 0; s < 3; ++s) {
    std::vector<double> q(n), v(n);
    for (size_t i = 0; i < n; ++i) {
      q[i] = 0.5 * u(rng);
      v[i] = u(rng);
    }
    const auto a = recursive.accelerations(0, q, v), ref = closed_form_chain(q, v);
    const double scale = std::max(1.0, max_abs(ref));
    for (size_t i = 0; i < n; ++i)
      EXPECT_LE(std::abs(a[i] - ref[i]), 1e-12 * scale)
          << "N = " << n << " state " << s << " q" << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Sizes, RecursiveChain, ::testing::Values(2, 5, 20, 50, 100, 200));

TEST(RecursiveDynamics, GrowsLinearlyWithTheChain) {
  const Model m50 = read_model_string(bench::links_chain_yaml(50), "<50>");
  const Model m100 = read_model_string(bench::links_chain_yaml(100), "<100>");
  const size_t d50 = derive(m50, Formulation::Recursive).definitions.size();
  const size_t d100 = derive(m100, Formulation::Recursive).definitions.size();
  EXPECT_NEAR(static_cast<double>(d100) / static_cast<double>(d50), 2.0, 0.05);
  const auto cm = compile(derive(m100, Formulation::Recursive));
  EXPECT_LT(cm->dynamics.num_instructions(), 400u * 100u);
}

/// Runs `model` recursively over t_end at tight tolerances: the energy stays to 1e-8 relative,
/// and q1 moves (the test is not of a system at rest).
void expect_energy_conserved(const Model& model, double t_end) {
  Formulated recursive(model, Formulation::Recursive);
  SimulationOptions so;
  so.t_end = t_end;
  so.output_step = t_end / 10;
  so.integrator.rtol = 1e-11;
  so.integrator.atol = 1e-12;
  const Trajectory traj =
      simulate(*recursive.dynamics, so, recursive.compiled->q0, recursive.compiled->v0);
  ASSERT_EQ(traj.status, Trajectory::Status::Complete) << traj.message;
  const double e0 = traj.at(0, "energy"), e1 = traj.at(traj.rows() - 1, "energy");
  EXPECT_LT(std::abs(e1 - e0), 1e-8 * std::abs(e0));
  EXPECT_GT(std::abs(traj.at(traj.rows() - 1, "q1") - traj.at(0, "q1")), 1e-3);
}

TEST(RecursiveDynamics, ConservesEnergyOfTheChain) {
  expect_energy_conserved(read_model_string(bench::links_chain_yaml(20), "<20>"), 2.0);
}

// A spatial chain (axes alternating x and y, every origin turned by rpy): its link poses nest
// full rotation products, whose expression DAG has exponentially many paths; the formulation
// must stay linear and conserve energy.
std::string spatial_chain(size_t n) {
  std::string y = "name: spatial chain\nparameters: {g: 9.81}\ngravity: [0, 0, -g]\nlinks:\n";
  for (size_t k = 1; k <= n; ++k) {
    y += "  l" + std::to_string(k) + ":\n";
    if (k > 1) y += "    parent: l" + std::to_string(k - 1) + "\n";
    y += "    joint: {name: q" + std::to_string(k) +
         ", type: revolute, axis: " + (k % 2 ? "[1, 0, 0]" : "[0, 1, 0]") +
         ", initial: 0.3, rate: 0.5" +
         (k > 1 ? ", origin: {xyz: [0, 0, -0.3], rpy: [0.1, 0.2, 0.3]}" : "") + "}\n";
    y += "    mass: 1\n    com: [0.05, 0, -0.15]\n    inertia: [0.012, 0.015, 0.006]\n";
  }
  return y;
}

TEST(RecursiveDynamics, SpatialChainStaysLinearAndConservesEnergy) {
  const Model m20 = read_model_string(spatial_chain(20), "<20>");
  const Model m40 = read_model_string(spatial_chain(40), "<40>");
  const size_t d20 = derive(m20, Formulation::Recursive).definitions.size();
  const size_t d40 = derive(m40, Formulation::Recursive).definitions.size();
  EXPECT_NEAR(static_cast<double>(d40) / static_cast<double>(d20), 2.0, 0.1);
  expect_energy_conserved(m40, 0.5);
}

TEST(RecursiveDynamics, SaysWhyItDoesNotApply) {
  const auto reason = [](const std::string& file) {
    return recursive_unsuitable(read_model_file(testing::example_path(file)));
  };
  EXPECT_EQ(reason("pendulum.yaml"), "it has no joint tree (links: or urdf:)");
  const std::string arm =
      "name: arm\nlinks:\n  a: {joint: {name: q1, type: revolute}, mass: 1, com: [1, 0, 0],"
      " inertia: [0, 0, 0], points: {tip: [1, 0, 0]}}\n";
  const auto with = [&](const std::string& extra) {
    return recursive_unsuitable(read_model_string(arm + extra, "<arm>"));
  };
  EXPECT_EQ(with(""), "");
  EXPECT_EQ(with("constraints: {on_axis: a.tip.y}\n"), "it has constraints");
  EXPECT_EQ(with("particles: {a.tip: 1}\n"), "it has particles");
  EXPECT_EQ(with("coordinates: {x: {initial: 0}}\nkinetic: der(x)^2/2\n"),
            "it has a written kinetic energy");
  const Model pendulum = read_model_file(testing::example_path("pendulum.yaml"));
  EXPECT_THROW((void)derive(pendulum, Formulation::Recursive), std::invalid_argument);
}

}  // namespace
}  // namespace lagrange
