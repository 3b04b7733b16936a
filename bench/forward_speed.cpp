// Forward dynamics per call against MuJoCo, in one run (issue: forward-dynamics speed).
// For the N-link pendulum (N = 2 … 100, per-link masses and lengths) and each URDF arm given on
// the command line: time per call (q, q̇, τ → q̈) of lagrange's tape interpreter, of its machine
// code (docs/theory.md §8), and of MuJoCo's mj_forward on the same chain (contacts, limits and
// passive forces off), each over the same 64 random states; plus what a user pays before the
// first call: derive + tape compile, and the C compiler run (uncached).
// The MuJoCo pendulum is the same chain in relative joint angles, its point masses carrying an
// inertia of 1e-6 kg m² (MuJoCo needs a positive one), so its per-call work is the same.
// The `links:` chain of the same masses and lengths in relative angles runs on the recursive
// formulation (docs/theory.md §4.9) for N = 2 … 200 (MuJoCo reads it as URDF), with its q̈
// checked against MuJoCo's at one state; each arm runs in both formulations.
// Usage: forward_speed [--max-n N] [ARM.urdf ...] (chains up to 2N); prints a Markdown table.

#include <mujoco/mujoco.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "n_link_pendulum.hpp"
#include "per_call_timer.hpp"

namespace {

using Clock = std::chrono::steady_clock;
using lagrange::bench::BuiltModel;
using lagrange::bench::kStates;
using lagrange::bench::microseconds_per_call;

/// The N-link pendulum as MJCF: hinges about z in the x–y plane, gravity −y, a point mass of
/// link k at its far end (k-th mass and length of the PerLink family).
std::string pendulum_mjcf(size_t n) {
  std::string s =
      "<mujoco><option gravity='0 -9.81 0'><flag contact='disable' limit='disable' "
      "passive='disable'/></option><worldbody>";
  for (size_t k = 1; k <= n; ++k) {
    const double l = lagrange::bench::per_link_length(k), m = lagrange::bench::per_link_mass(k);
    s += "<body pos='" +
         std::string(k == 1
                         ? "0 0 0"
                         : "0 " + std::to_string(-lagrange::bench::per_link_length(k - 1)) + " 0") +
         "'><joint type='hinge' axis='0 0 1'/><inertial pos='0 " + std::to_string(-l) +
         " 0' mass='" + std::to_string(m) + "' diaginertia='1e-6 1e-6 1e-6'/>";
  }
  for (size_t k = 0; k < n; ++k) s += "</body>";
  return s + "</worldbody></mujoco>";
}

/// The links chain of links_chain_yaml(n, 1e-6) as URDF, which MuJoCo reads for any N (its XML
/// reader cannot nest 100 MJCF bodies; URDF lists links flat). Gravity is set to −y after loading.
std::string chain_urdf(size_t n) {
  std::string s = "<robot name='chain'><link name='base'/>";
  for (size_t k = 1; k <= n; ++k) {
    const double l = lagrange::bench::per_link_length(k), m = lagrange::bench::per_link_mass(k);
    const double offset = k == 1 ? 0.0 : lagrange::bench::per_link_length(k - 1);
    s += "<link name='l" + std::to_string(k) + "'><inertial><origin xyz='0 " + std::to_string(-l) +
         " 0'/><mass value='" + std::to_string(m) +
         "'/><inertia ixx='1e-6' iyy='1e-6' izz='1e-6' ixy='0' ixz='0' iyz='0'/></inertial></link>";
    s += "<joint name='q" + std::to_string(k) + "' type='continuous'><parent link='" +
         (k == 1 ? std::string("base") : "l" + std::to_string(k - 1)) + "'/><child link='l" +
         std::to_string(k) + "'/><origin xyz='0 " + std::to_string(-offset) +
         " 0'/><axis xyz='0 0 1'/></joint>";
  }
  return s + "</robot>";
}

mjModel* load_mujoco(const std::string& xml_or_path, bool is_text, const char* suffix = ".xml") {
  std::string path = xml_or_path;
  if (is_text) {
    path = (std::filesystem::temp_directory_path() /
            ("lagrange-forward-speed-" + std::to_string(::getpid()) + suffix))
               .string();
    std::ofstream(path) << xml_or_path;
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  if (is_text) std::filesystem::remove(path);
  if (m == nullptr) {
    // MuJoCo 2.2.2's XML reader stops at 100 nested elements: a 100-link chain cannot be
    // written as MJCF at all. The row then shows no MuJoCo figure.
    std::fprintf(stderr, "MuJoCo cannot load %s: %s\n", is_text ? "the MJCF" : path.c_str(), error);
    return nullptr;
  }
  m->opt.disableflags |= mjDSBL_CONTACT | mjDSBL_LIMIT | mjDSBL_PASSIVE;
  for (int i = 0; i < m->nv; ++i) m->dof_armature[i] = m->dof_frictionloss[i] = 0;
  return m;
}

struct Row {
  std::string name;
  size_t dof = 0, instructions = 0;
  double build_s = 0, cc_s = 0, interp_us = 0, native_us = 0, mujoco_us = 0;
  double agreement = std::nan("");  ///< max |q̈ − MuJoCo's| / max(1, |q̈|∞) at one state
};

/// Our q̈ against MuJoCo's qacc at the same state, for a model whose coordinates are MuJoCo's
/// joints in the same order (the chains).
double agreement(lagrange::Dynamics& dyn, mjModel* m, const std::vector<double>& q,
                 const std::vector<double>& v) {
  const lagrange::CompiledModel& cm = dyn.model();
  std::vector<double> qdot(cm.nq), a(cm.nv);
  dyn.forward(0.0, q.data(), v.data(), qdot.data(), a.data(), nullptr);
  mjData* d = mj_makeData(m);
  std::copy(q.begin(), q.end(), d->qpos);
  std::copy(v.begin(), v.end(), d->qvel);
  mj_forward(m, d);
  double worst = 0, scale = 1;
  for (size_t i = 0; i < cm.nv; ++i) {
    worst = std::max(worst, std::abs(a[i] - d->qacc[i]));
    scale = std::max(scale, std::abs(a[i]));
  }
  mj_deleteData(d);
  return worst / scale;
}

Row measure(const std::string& name, BuiltModel b, mjModel* m, bool same_joints = false) {
  Row row;
  row.name = name;
  const lagrange::CompiledModel& cm = *b.compiled;
  row.dof = cm.nv;
  row.build_s = b.times.build();
  row.instructions = lagrange::bench::specialised_instructions(cm);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::vector<double>> qs(kStates, cm.q0), vs(kStates, cm.v0);
  for (size_t s = 0; s < kStates; ++s)
    for (size_t i = 0; i < cm.nv; ++i) {
      qs[s][i] += 0.5 * u(rng);
      vs[s][i] = u(rng);
    }
  std::vector<double> qdot(cm.nq), a(cm.nv), lambda(cm.m + 1);
  lagrange::Dynamics& dyn = *b.dynamics;
  auto call = [&](size_t s) {
    dyn.forward(0.0, qs[s].data(), vs[s].data(), qdot.data(), a.data(), lambda.data());
  };
  row.interp_us = microseconds_per_call(call);
  // A private, empty cache: the compiler run is timed, not a cache hit.
  lagrange::MachineCodeOptions options;
  options.cache_dir = (std::filesystem::temp_directory_path() /
                       ("lagrange-forward-speed-cache-" + std::to_string(::getpid())))
                          .string();
  std::filesystem::remove_all(options.cache_dir);
  const auto t0 = Clock::now();
  dyn.set_evaluation(lagrange::Evaluation::MachineCode, options);
  row.cc_s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::filesystem::remove_all(options.cache_dir);
  if (!dyn.uses_machine_code()) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), dyn.evaluation_note().c_str());
    std::exit(1);
  }
  row.native_us = microseconds_per_call(call);
  if (m == nullptr) {
    row.mujoco_us = std::nan("");
    return row;
  }
  if (same_joints) row.agreement = agreement(dyn, m, qs[0], vs[0]);
  mjData* d = mj_makeData(m);
  std::vector<std::vector<double>> mq(kStates), mv(kStates);
  for (size_t s = 0; s < kStates; ++s)
    for (int i = 0; i < m->nv; ++i) {
      mq[s].push_back(0.5 * u(rng));
      mv[s].push_back(u(rng));
    }
  row.mujoco_us = microseconds_per_call([&](size_t s) {
    std::copy(mq[s].begin(), mq[s].end(), d->qpos);
    std::copy(mv[s].begin(), mv[s].end(), d->qvel);
    mj_forward(m, d);
  });
  mj_deleteData(d);
  mj_deleteModel(m);
  return row;
}

std::string fmt_sci(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1e", x);
  return buf;
}

}  // namespace

int main(int argc, char** argv) {
  size_t max_n = 100;
  std::vector<std::string> arms;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--max-n" && i + 1 < argc)
      max_n = static_cast<size_t>(std::atol(argv[++i]));
    else
      arms.push_back(arg);
  }
  std::vector<Row> rows;
  for (size_t n : {2, 5, 10, 20, 50, 100}) {
    if (n > max_n) break;
    const std::string label = "pendulum N=" + std::to_string(n);
    rows.push_back(measure(
        label,
        lagrange::bench::build_model(lagrange::bench::n_link_pendulum_yaml(n), "<" + label + ">"),
        load_mujoco(pendulum_mjcf(n), true)));
    std::fprintf(stderr, "%s done\n", label.c_str());
  }
  // The same chain as `links:` in relative angles, recursive (docs/theory.md §4.9); MuJoCo reads
  // it as URDF, so every N loads.
  // Up to N = 20 the Lagrangian formulation of the same chain too: where `--dynamics auto`
  // should switch.
  for (size_t n : {2, 5, 10, 20, 50, 100, 200}) {
    if (n > 2 * max_n) break;
    for (const auto form : {lagrange::Formulation::Lagrangian, lagrange::Formulation::Recursive}) {
      const bool recursive = form == lagrange::Formulation::Recursive;
      if (!recursive && n > 20) continue;
      const std::string label =
          "chain N=" + std::to_string(n) + (recursive ? " recursive" : " Lagrangian");
      mjModel* m = load_mujoco(chain_urdf(n), true, ".urdf");
      if (m != nullptr) {
        m->opt.gravity[0] = 0;
        m->opt.gravity[1] = -9.81;
        m->opt.gravity[2] = 0;
      }
      rows.push_back(
          measure(label,
                  lagrange::bench::build_model(lagrange::bench::links_chain_yaml(n, 1e-6),
                                               "<" + label + ">", form),
                  m, true));
      std::fprintf(stderr, "%s done\n", label.c_str());
    }
  }
  for (const auto& path : arms)
    for (const auto form : {lagrange::Formulation::Lagrangian, lagrange::Formulation::Recursive}) {
      const bool recursive = form == lagrange::Formulation::Recursive;
      rows.push_back(measure(
          std::filesystem::path(path).stem().string() + (recursive ? " recursive" : " Lagrangian"),
          lagrange::bench::build_model_file(path, form), load_mujoco(path, false)));
    }
  std::printf(
      "| model | dof | tape instr. | derive+compile s | cc s | interpreter µs | machine code µs | "
      "MuJoCo mj_forward µs | MuJoCo / machine code | q̈ vs MuJoCo |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& r : rows)
    std::printf("| %s | %zu | %zu | %.3f | %.2f | %.3f | %.3f | %.3f | %.2f× | %s |\n",
                r.name.c_str(), r.dof, r.instructions, r.build_s, r.cc_s, r.interp_us, r.native_us,
                r.mujoco_us, r.mujoco_us / r.native_us,
                std::isnan(r.agreement) ? "" : fmt_sci(r.agreement).c_str());
  return 0;
}
