// MuJoCo peer of bench/work_precision.cpp (docs/benchmarks.md, "Work-precision"): MuJoCo 2.2.2's
// fixed-step RK4 (mjINT_RK4, mj_step: four mj_forward per step) on the planar pendulum chains
// the C++ program measures — the double pendulum of examples/ and the N = 10 and N = 50
// per-link chains — swept over the step h = 0.1 s / 2^j, so that the step reaching a given error
// can be read off. The error is the largest |θ − θ_ref| of the absolute angles over the samples
// (every 0.1 s, each a step end) against the reference work_precision wrote (arkode:verner65 at
// rtol 1e-13). Contacts, joint limits and passive forces are off; each point mass carries an
// inertia of 1e-14 kg m² (MuJoCo needs a positive one). Halving h stops once the error no longer
// falls, at the floor of the reference and of that inertia: about 4e-8 on the chaotic double
// pendulum over 10 s, 5e-13 and 3e-12 on the chains (with 1e-12 kg m², 3e-11 on the chains).
//   work_precision_mujoco REFERENCE_DIR     one JSON line per run, like work_precision

#include <fmt/format.h>
#include <mujoco/mujoco.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "n_link_pendulum.hpp"

namespace {

using lagrange::bench::Stopwatch;

/// A planar pendulum chain: point mass masses[k] at the end of link k of length lengths[k],
/// initial absolute angles, at rest, simulated for t_end seconds.
struct Chain {
  std::string name;
  std::vector<double> masses, lengths, angles;
  double t_end;
};

/// The chain as MJCF: hinges about z in the x–y plane, gravity −y, joint angles relative to the
/// parent link (θ_k − θ_{k−1} in the absolute angles of the lagrange models).
std::string chain_mjcf(const Chain& c) {
  std::string s =
      "<mujoco><option gravity='0 -9.81 0' integrator='RK4'><flag contact='disable' "
      "limit='disable' passive='disable'/></option><worldbody>";
  for (size_t k = 0; k < c.masses.size(); ++k) {
    s += fmt::format(
        "<body pos='0 {:.17g} 0'><joint type='hinge' axis='0 0 1'/><inertial pos='0 {:.17g} 0' "
        "mass='{:.17g}' diaginertia='1e-14 1e-14 1e-14'/>",
        k == 0 ? 0.0 : -c.lengths[k - 1], -c.lengths[k], c.masses[k]);
  }
  for (size_t k = 0; k < c.masses.size(); ++k) s += "</body>";
  return s + "</worldbody></mujoco>";
}

/// mj_loadXML reads only files: the MJCF goes through a temporary one.
mjModel* load(const std::string& mjcf) {
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("lagrange-work-precision-" + std::to_string(::getpid()) + ".xml"))
                               .string();
  std::ofstream(path) << mjcf;
  char error[1000] = "";
  mjModel* m = mj_loadXML(path.c_str(), nullptr, error, sizeof error);
  std::filesystem::remove(path);
  if (m == nullptr) fmt::print(stderr, "MuJoCo cannot load the chain: {}\n", error);
  return m;
}

/// The "q" array of REFERENCE_DIR/reference_<name>.json (t and q per sample, written by
/// work_precision): the numbers between the brackets after "q".
std::vector<double> reference(const std::string& dir, const std::string& name) {
  std::ifstream in(dir + "/reference_" + name + ".json");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t open = text.find('[', text.find("\"q\""));
  std::vector<double> q;
  if (open == std::string::npos) return q;
  const char* p = text.c_str() + open + 1;
  for (char* end = nullptr;; p = end + 1) {
    const double x = std::strtod(p, &end);
    if (end == p) break;
    q.push_back(x);
    while (*end == ' ') ++end;
    if (*end != ',') break;
  }
  return q;
}

std::vector<Chain> chains() {
  std::vector<Chain> out{{"double_pendulum", {1.0, 1.0}, {1.0, 1.0}, {1.5, 2.5}, 10.0}};
  for (const auto& [n, t_end] : {std::pair<size_t, double>{10, 5.0}, {50, 1.0}}) {
    Chain c{"chain_" + std::to_string(n), {}, {}, {}, t_end};
    for (size_t k = 1; k <= n; ++k) {
      c.masses.push_back(lagrange::bench::per_link_mass(k));
      c.lengths.push_back(lagrange::bench::per_link_length(k));
      c.angles.push_back(lagrange::bench::initial_angle(k));
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : ".";
  // MuJoCo warns (e.g. of a diverging step) on stdout, which carries the JSON lines.
  mju_user_warning = [](const char* message) { fmt::print(stderr, "MuJoCo: {}\n", message); };
  for (const Chain& c : chains()) {
    const std::vector<double> q_ref = reference(dir, c.name);
    const size_t n = c.masses.size();
    const long samples = std::lround(c.t_end / 0.1);
    if (q_ref.size() != n * static_cast<size_t>(samples + 1)) {
      fmt::print(stderr, "{}: no reference in {} (run work_precision first)\n", c.name, dir);
      return 1;
    }
    mjModel* m = load(chain_mjcf(c));
    if (m == nullptr) return 1;
    mjData* d = mj_makeData(m);
    double previous = HUGE_VAL;
    for (int j = 1; j <= 13; ++j) {
      const long per_sample = 1L << j;
      m->opt.timestep = 0.1 / static_cast<double>(per_sample);
      mj_resetData(m, d);
      for (size_t k = 0; k < n; ++k) d->qpos[k] = c.angles[k] - (k == 0 ? 0.0 : c.angles[k - 1]);
      double error = 0.0;
      const Stopwatch clock;
      const auto start = clock.now();
      for (long s = 1; s <= samples; ++s) {
        for (long i = 0; i < per_sample; ++i) mj_step(m, d);
        double theta = 0.0;  // absolute angle: the sum of the relative ones
        for (size_t k = 0; k < n; ++k) {
          theta += d->qpos[k];
          error = std::max(error, std::abs(theta - q_ref[static_cast<size_t>(s) * n + k]));
        }
      }
      const auto end = clock.now();
      if (!std::isfinite(error)) error = HUGE_VAL;
      const long steps = samples * per_sample;
      fmt::print(
          "{{\"engine\": \"mujoco\", \"model\": \"{}\", \"method\": \"mujoco:RK4\", \"ran\": "
          "\"mujoco:RK4\", \"step\": {:g}, \"error\": {:.3e}, \"rhs_evals\": {}, \"steps\": {}, "
          "\"wall_s\": {:.6f}, \"cpu_s\": {:.6f}}}\n",
          c.name, m->opt.timestep, error, 4 * steps, steps, end.wall - start.wall,
          end.cpu - start.cpu);
      std::fflush(stdout);
      if (error < 1e-5 && error > 0.5 * previous) break;  // the floor: no gain from halving h
      previous = error;
    }
    mj_deleteData(d);
    mj_deleteModel(m);
  }
  return 0;
}
