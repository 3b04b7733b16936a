// Pinocchio's articulated-body algorithm on the chain of bench/forward_speed.cpp, timed the same
// way (per_call_timer.hpp), as the peer of the recursive formulation (docs/theory.md §4.9).
// Built header-only from Pinocchio's public source by bench/pinocchio.sh, outside the product's
// dependencies. The chain: revolute joints about z, link k's point mass m_k at [0, −l_k, 0] with
// 1e-6 kg m² about it, joint k at [0, −l_{k−1}, 0] in link k−1, gravity −y: links_chain_yaml(N,
// 1e-6) and the MuJoCo URDF of forward_speed. Also prints q̈ at one fixed state per N, so that
// the numbers can be compared with `lagrange eval` (docs/benchmarks.md).
// Usage: pinocchio_aba [N ...] (default 2 5 10 20 50 100 200); prints a Markdown table.

#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "n_link_pendulum.hpp"
#include "per_call_timer.hpp"
#include "pinocchio/algorithm/aba.hpp"
#include "pinocchio/multibody/data.hpp"
#include "pinocchio/multibody/model.hpp"

namespace {

pinocchio::Model chain(std::size_t n) {
  pinocchio::Model model;
  model.gravity.linear() << 0, -9.81, 0;
  pinocchio::JointIndex parent = 0;
  for (std::size_t k = 1; k <= n; ++k) {
    pinocchio::SE3 place = pinocchio::SE3::Identity();
    place.translation() << 0, k == 1 ? 0.0 : -lagrange::bench::per_link_length(k - 1), 0;
    parent = model.addJoint(parent, pinocchio::JointModelRZ(), place, "q" + std::to_string(k));
    model.appendBodyToJoint(
        parent, pinocchio::Inertia(lagrange::bench::per_link_mass(k),
                                   Eigen::Vector3d(0, -lagrange::bench::per_link_length(k), 0),
                                   Eigen::Matrix3d::Identity() * 1e-6));
  }
  return model;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::size_t> sizes;
  for (int i = 1; i < argc; ++i) sizes.push_back(static_cast<std::size_t>(std::atol(argv[i])));
  if (sizes.empty()) sizes = {2, 5, 10, 20, 50, 100, 200};
  std::printf(
      "| chain | Pinocchio ABA, local µs | Pinocchio ABA, world µs | q̈₁ at q = 0.3, q̇ = 0.5 |\n"
      "|---|---|---|---|\n");
  for (const std::size_t n : sizes) {
    const pinocchio::Model model = chain(n);
    pinocchio::Data data(model);
    std::mt19937_64 rng(42);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<Eigen::VectorXd> qs, vs;
    for (std::size_t s = 0; s < lagrange::bench::kStates; ++s) {
      qs.emplace_back(Eigen::VectorXd::NullaryExpr(model.nq, [&] { return 0.5 * u(rng); }));
      vs.emplace_back(Eigen::VectorXd::NullaryExpr(model.nv, [&] { return u(rng); }));
    }
    const Eigen::VectorXd tau = Eigen::VectorXd::Zero(model.nv);
    const double local = lagrange::bench::microseconds_per_call([&](std::size_t s) {
      pinocchio::aba(model, data, qs[s], vs[s], tau, pinocchio::Convention::LOCAL);
    });
    const double world = lagrange::bench::microseconds_per_call([&](std::size_t s) {
      pinocchio::aba(model, data, qs[s], vs[s], tau, pinocchio::Convention::WORLD);
    });
    pinocchio::aba(model, data, Eigen::VectorXd::Constant(model.nq, 0.3),
                   Eigen::VectorXd::Constant(model.nv, 0.5), tau, pinocchio::Convention::LOCAL);
    std::printf("| N = %zu | %.3f | %.3f | %.15g |\n", n, local, world, data.ddq[0]);
  }
  return 0;
}
