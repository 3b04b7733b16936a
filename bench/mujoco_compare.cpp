// Accuracy against MuJoCo (issue 11): loads URDF arms into MuJoCo and into lagrange and compares
// the mass matrix M, the bias forces C(q, q̇) q̇ + g(q) and the accelerations q̈ (zero torques) at
// random states, printing the worst relative differences. Joint damping from the file acts in
// both (a passive force in MuJoCo, Q = −b q̇ here); MuJoCo's armature and friction loss are
// zeroed and its contacts and joint limits disabled.
// MuJoCo 2.2.2 diagonalises each full inertia tensor numerically, accurate only to about 1e-8
// (1e-7 in q̈ for the Panda). So each file is compared twice: as MuJoCo loads it, and with every
// body's principal inertia and frame recomputed from the URDF tensor (the one lagrange uses) by
// Eigen's symmetric eigensolver; the tolerance (1e-9 unless given) applies to the second.
// MuJoCo's fusing of fixed links is switched off so that its bodies are the URDF links.
// Usage: mujoco_compare [--tol T] FILE.urdf... (exit 1 when a difference exceeds T).

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
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

/// MuJoCo's model of the URDF at `path` with fixed links kept as bodies (a copy of the file with
/// <mujoco><compiler fusestatic="false"/></mujoco> written beside it), or null with `error`.
mjModel* load_unfused(const std::string& path, char* error, int size) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::string xml = text.str();
  const size_t robot = xml.find('>', xml.find("<robot"));
  if (robot == std::string::npos) return nullptr;
  xml.insert(robot + 1, "<mujoco><compiler fusestatic=\"false\" discardvisual=\"true\"/></mujoco>");
  const std::string copy = path + ".mujoco_compare.urdf";
  std::ofstream(copy) << xml;
  mjModel* m = mj_loadXML(copy.c_str(), nullptr, error, size);
  std::filesystem::remove(copy);
  return m;
}

/// Replaces MuJoCo's principal inertias and inertial frames by the eigen-decomposition of each
/// link's tensor as lagrange reads it (exact decimals, rotated into the link frame).
void install_exact_inertias(mjModel* m, const lagrange::Model& model, const GiNaC::exmap& params) {
  for (const lagrange::Body& b : model.bodies) {
    const int id = mj_name2id(m, mjOBJ_BODY, b.name.c_str());
    if (id < 0) continue;
    Eigen::Matrix3d I;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) I(r, c) = at(b.inertia[r][c], params);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
    Eigen::Matrix3d R = eig.eigenvectors();
    if (R.determinant() < 0) R.col(2) *= -1;
    const Eigen::Quaterniond quat(R);
    const double wxyz[4] = {quat.w(), quat.x(), quat.y(), quat.z()};
    for (int k = 0; k < 3; ++k) {
      m->body_inertia[3 * id + k] = eig.eigenvalues()[k];
      m->body_ipos[3 * id + k] = at(b.com[k], params);
    }
    for (int k = 0; k < 4; ++k) m->body_iquat[4 * id + k] = wxyz[k];
    m->body_mass[id] = at(b.mass, params);
    // The compiler's shortcuts for bodies whose inertial frame is the body frame, or whose M is
    // diagonal, assume its own values: switch them off.
    m->body_sameframe[id] = 0;
    m->body_simple[id] = 0;
  }
  for (int i = 0; i < m->nv; ++i) m->dof_simplenum[i] = 0;
}

struct Worst {
  double M = 0, bias = 0, acc = 0;
};

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
    mjModel* m = load_unfused(path, error, sizeof error);
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
    auto compare = [&]() {
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> u(-2, 2);
      Worst w;
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
        w.M = std::max(w.M, relative(M, Mj));
        w.bias = std::max(w.bias, relative(bias, bias_j));
        w.acc = std::max(w.acc, relative(acc, acc_j));
      }
      return w;
    };
    const Worst loaded = compare();
    install_exact_inertias(m, model, params);
    const Worst exact = compare();
    std::printf(
        "%s: %d joints, 10 random states, worst relative difference in M, bias, qddot:\n"
        "  MuJoCo's own inertia diagonalisation:  %.2e  %.2e  %.2e\n",
        path.c_str(), n, loaded.M, loaded.bias, loaded.acc);
    const double worst_M = exact.M, worst_bias = exact.bias, worst_a = exact.acc;
    const bool ok = worst_M < tol && worst_bias < tol && worst_a < tol;
    std::printf("  inertias recomputed from the URDF:     %.2e  %.2e  %.2e%s\n", worst_M,
                worst_bias, worst_a, ok ? "" : "  (above the tolerance)");
    if (!ok) status = 1;
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  return status;
}
