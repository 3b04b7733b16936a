// Accuracy against MuJoCo (issue 11): loads URDF arms into MuJoCo and into lagrange and compares
// the mass matrix M, the bias forces C(q, q̇) q̇ + g(q) and the accelerations q̈ (zero torques) at
// random states, printing the worst relative differences. Joint damping from the file acts in
// both (a passive force in MuJoCo, Q = −b q̇ here); MuJoCo's armature and friction loss are
// zeroed and its contacts and joint limits disabled.
// MuJoCo 2.2.2 diagonalises each inertia tensor numerically, which is accurate to about 1e-8
// for full tensors in rotated inertial frames; the tolerance is 1e-9 unless given.
// Usage: mujoco_compare [--tol T] FILE.urdf... (exit 1 when a difference exceeds T).

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/reader.hpp"

namespace {

double relative(const Eigen::MatrixXd& ours, const Eigen::MatrixXd& theirs) {
  return (ours - theirs).cwiseAbs().maxCoeff() / std::max(1e-300, theirs.cwiseAbs().maxCoeff());
}

double at(const GiNaC::ex& e, const GiNaC::exmap& values) {
  return GiNaC::ex_to<GiNaC::numeric>(e.subs(values).evalf()).to_double();
}

}  // namespace

int main(int argc, char** argv) {
  int status = 0;
  double tol = 1e-9;
  for (int f = 1; f < argc; ++f) {
    if (std::string(argv[f]) == "--tol" && f + 1 < argc) {
      tol = std::atof(argv[++f]);
      continue;
    }
    const std::string path = argv[f];
    char error[1000] = "";
    mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
    if (!m) {
      std::fprintf(stderr, "%s: MuJoCo cannot load it: %s\n", path.c_str(), error);
      return 2;
    }
    m->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_LIMIT;
    for (int i = 0; i < m->nv; ++i) m->dof_armature[i] = m->dof_frictionloss[i] = 0;
    mjData* d = mj_makeData(m);
    const lagrange::Model model = lagrange::read_model_file(path);
    const lagrange::Equations eq = lagrange::derive(model);
    const auto cm = lagrange::compile(eq);
    lagrange::Dynamics dyn(cm, cm->parameter_defaults);
    const int n = static_cast<int>(eq.nv);
    if (n != m->nv) {
      std::fprintf(stderr, "%s: %d coordinates here, %d in MuJoCo\n", path.c_str(), n, m->nv);
      return 2;
    }
    // Our coordinate i is MuJoCo's joint of the same name.
    std::vector<int> dof(n);
    for (int i = 0; i < n; ++i) {
      const int j = mj_name2id(m, mjOBJ_JOINT, model.coordinates[i].name.c_str());
      if (j < 0) {
        std::fprintf(stderr, "%s: no MuJoCo joint '%s'\n", path.c_str(),
                     model.coordinates[i].name.c_str());
        return 2;
      }
      dof[i] = m->jnt_dofadr[j];
    }
    GiNaC::exmap params;
    for (const auto& p : model.parameters) params[p.sym] = p.value;
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-2, 2);
    double worst_M = 0, worst_bias = 0, worst_a = 0;
    for (int s = 0; s < 10; ++s) {
      std::vector<double> q(n), v(n), qdot(n), a(n);
      GiNaC::exmap values = params;
      for (int i = 0; i < n; ++i) {
        q[i] = u(rng);
        v[i] = u(rng);
        values[eq.kin.q[i]] = q[i];
        values[eq.kin.v[i]] = v[i];
        d->qpos[m->jnt_qposadr[m->dof_jntid[dof[i]]]] = q[i];
        d->qvel[dof[i]] = v[i];
      }
      mj_forward(m, d);
      std::vector<mjtNum> full(static_cast<size_t>(m->nv * m->nv));
      mj_fullM(m, full.data(), d->qM);
      Eigen::MatrixXd M(n, n), Mj(n, n), bias(n, 1), bias_j(n, 1), acc(n, 1), acc_j(n, 1);
      dyn.forward(0, q.data(), v.data(), qdot.data(), a.data(), nullptr);
      for (int i = 0; i < n; ++i) {
        for (int k = 0; k < n; ++k) {
          M(i, k) = at(eq.M(i, k), values);
          Mj(i, k) = full[static_cast<size_t>(dof[i] * m->nv + dof[k])];
        }
        bias(i, 0) = -at(eq.h[i], values);
        bias_j(i, 0) = d->qfrc_bias[dof[i]];
        acc(i, 0) = a[i];
        acc_j(i, 0) = d->qacc[dof[i]];
      }
      worst_M = std::max(worst_M, relative(M, Mj));
      worst_bias = std::max(worst_bias, relative(bias, bias_j));
      worst_a = std::max(worst_a, relative(acc, acc_j));
    }
    const bool ok = worst_M < tol && worst_bias < tol && worst_a < tol;
    std::printf(
        "%s: %d joints, 10 random states: worst relative difference M %.2e, bias %.2e, "
        "qddot %.2e%s\n",
        path.c_str(), n, worst_M, worst_bias, worst_a, ok ? "" : "  (above the tolerance)");
    if (!ok) status = 1;
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  return status;
}
