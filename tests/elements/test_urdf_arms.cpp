// The real arm descriptions in examples/robots (UR5, Franka Panda): read with one coordinate per
// movable joint, Ḋ − 2C skew-symmetric at random states (numerically, docs/theory.md §4.8), the
// Euler–Lagrange forcing equal to −C q̇ − g, and the generic forward dynamics equal to the
// manipulator form's D⁻¹(τ − C q̇ − g) with inverse dynamics returning τ.

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "support/test_paths.hpp"
#include "lagrange/tape.hpp"
#include "support/harness.hpp"

namespace lagrange {
namespace {

std::string robot(const std::string& file) {
  return std::string(LAGRANGE_SOURCE_DIR) + "/examples/robots/" + file;
}

/// D, ∂D/∂q_l, h, g = ∂U/∂q and Q of an arm, compiled once and evaluated at states.
class ArmTerms {
 public:
  explicit ArmTerms(const Equations& eq) : n_(eq.nv) {
    std::vector<GiNaC::ex> out;
    for (size_t i = 0; i < n_; ++i)
      for (size_t j = 0; j < n_; ++j) out.push_back(eq.M(i, j));
    for (size_t l = 0; l < n_; ++l)
      for (size_t i = 0; i < n_; ++i)
        for (size_t j = 0; j < n_; ++j) out.push_back(eq.M(i, j).diff(eq.kin.q[l]));
    for (size_t k = 0; k < n_; ++k) out.push_back(eq.h[k]);
    for (size_t k = 0; k < n_; ++k) out.push_back(eq.U.diff(eq.kin.q[k]));
    for (size_t k = 0; k < n_; ++k) out.push_back(eq.Q[k]);
    tape_ = Tape::compile(out, eq.tape_inputs());
  }
  /// Evaluates at the tape inputs `in` (t, q, v, u, p).
  void at(const std::vector<double>& in) {
    values_.resize(tape_.num_outputs());
    std::vector<double> work(tape_.work_size());
    tape_.eval(in.data(), values_.data(), work.data());
  }
  double D(size_t i, size_t j) const { return values_[i * n_ + j]; }
  double dD(size_t l, size_t i, size_t j) const { return values_[n_ * n_ * (1 + l) + i * n_ + j]; }
  double h(size_t k) const { return values_[n_ * n_ * (n_ + 1) + k]; }
  double g(size_t k) const { return values_[n_ * n_ * (n_ + 1) + n_ + k]; }
  double Q(size_t k) const { return values_[n_ * n_ * (n_ + 1) + 2 * n_ + k]; }

 private:
  size_t n_;
  Tape tape_;
  std::vector<double> values_;
};

void expect_manipulator_identities(const std::string& file, size_t joints) {
  auto sys = testing::load_model(std::make_unique<Model>(read_model_file(robot(file))));
  const Equations eq = derive(*sys.model);
  ASSERT_EQ(eq.nv, joints);
  ASSERT_EQ(eq.m, 0u);
  const size_t n = eq.nv;
  ArmTerms terms(eq);
  std::mt19937 rng(2026);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int s = 0; s < 5; ++s) {
    std::vector<double> q(n), v(n), qdot(n), a(n);
    for (size_t i = 0; i < n; ++i) {
      q[i] = u(rng);
      v[i] = u(rng);
    }
    sys.dynamics->forward(0, q.data(), v.data(), qdot.data(), a.data(), nullptr);
    terms.at(sys.dynamics->last_inputs());
    // C_kj = Σᵢ c_ijk q̇ᵢ, c_ijk = ½(∂d_kj/∂qᵢ + ∂d_ki/∂qⱼ − ∂d_ij/∂q_k); N = Ḋ − 2C.
    Eigen::MatrixXd D(n, n), C(n, n), N(n, n);
    Eigen::VectorXd b(n), tau(n), qdd(n), vv(n);
    for (size_t k = 0; k < n; ++k) {
      vv[static_cast<Eigen::Index>(k)] = v[k];
      for (size_t j = 0; j < n; ++j) {
        double c = 0, ddot = 0;
        for (size_t i = 0; i < n; ++i) {
          c += 0.5 * (terms.dD(i, k, j) + terms.dD(j, k, i) - terms.dD(k, i, j)) * v[i];
          ddot += terms.dD(i, k, j) * v[i];
        }
        const auto K = static_cast<Eigen::Index>(k), J = static_cast<Eigen::Index>(j);
        D(K, J) = terms.D(k, j);
        C(K, J) = c;
        N(K, J) = ddot - 2 * c;
      }
    }
    EXPECT_LT((N + N.transpose()).cwiseAbs().maxCoeff(), 1e-12 * N.cwiseAbs().maxCoeff())
        << file << ", state " << s;
    for (size_t k = 0; k < n; ++k) {
      const auto K = static_cast<Eigen::Index>(k);
      b[K] = (C * vv)[K] + terms.g(k);
      tau[K] = terms.Q(k);
      EXPECT_NEAR(terms.h(k) + b[K], 0, 1e-10 * (1 + std::abs(b[K]))) << file << ", row " << k;
    }
    // Forward dynamics of the manipulator form and of the generic path agree; inverse dynamics
    // D q̈ + C q̇ + g of that q̈ returns τ.
    qdd = D.llt().solve(tau - b);
    const Eigen::VectorXd tau_back = D * qdd + b;
    for (size_t k = 0; k < n; ++k) {
      const auto K = static_cast<Eigen::Index>(k);
      EXPECT_NEAR(qdd[K], a[k], 1e-10 * (1 + std::abs(a[k]))) << file << ", joint " << k;
      EXPECT_NEAR(tau_back[K], tau[K], 1e-10 * (1 + b.cwiseAbs().maxCoeff())) << file << k;
    }
  }
}

TEST(UrdfArms, Ur5ManipulatorIdentitiesAtRandomStates) {
  expect_manipulator_identities("ur5.urdf", 6);
}

TEST(UrdfArms, PandaManipulatorIdentitiesAtRandomStates) {
  expect_manipulator_identities("panda.urdf", 7);
}

TEST(UrdfArms, JointsAreTheMovableUrdfJoints) {
  const Model panda = read_model_file(robot("panda.urdf"));
  ASSERT_EQ(panda.coordinates.size(), 7u);
  for (size_t i = 0; i < 7; ++i)
    EXPECT_EQ(panda.coordinates[i].name, "panda_joint" + std::to_string(i + 1));
  const Model ur5 = read_model_file(robot("ur5.urdf"));
  ASSERT_EQ(ur5.coordinates.size(), 6u);
  EXPECT_EQ(ur5.coordinates[0].name, "shoulder_pan_joint");
  EXPECT_EQ(ur5.coordinates[5].name, "wrist_3_joint");
}

}  // namespace
}  // namespace lagrange
