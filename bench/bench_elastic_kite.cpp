// KPS4-like case of issue 22: the rigid AP2 of examples/rigid_kite_ap2.yaml, its control laws
// unchanged, on a 6-segment *elastic* Dyneema tether (docs/theory.md §4.10) with simple drag in
// a logarithmic wind (6 m/s at 10 m, z₀ = 0.1 m). Line data: d = 2 mm, μ = 4.6 g/m
// (awebox opts/kite_data/ampyx_ap2_settings.py), E = 100 GPa (awebox opts/default.py), so EA = E π
// d²/4 = 314 kN; the damping D = 1000 N·s (on the strain rate) is this benchmark's choice. It flies
// 60 s against a reference run at rtol 1e-12 and reports, per rtol (1e-3, 1e-6), the CPU seconds of
// this process, the real-time factor and the largest error over the output samples (every 0.05 s)
// of the kite's position and the ground tension. KiteModels.jl's KPS4 on 6 segments: 117× (reeling)
// to 239× (parked), issue 22.
//   bench_elastic_kite [--quick] [--integrator METHOD]   (--quick: 5 s of flight)

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "bench_support.hpp"
#include "lagrange/integrator.hpp"
#include "lagrange/simulation.hpp"

namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("rigid_kite_ap2.yaml lacks " + from);
  return text.replace(at, from.size(), to);
}

std::string elastic_kite_yaml() {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/examples/rigid_kite_ap2.yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = replaced(ss.str(), "segments: 5", "segments: 6");
  text = replaced(text, "drag: simple}", "drag: simple, elasticity: {EA: 314159, damping: 1000}}");
  return replaced(text, "wind: {speed: W}",
                  "wind: {profile: logarithmic, speed: W, reference_height: 10, roughness: 0.1}");
}

struct Errors {
  double position = 0, tension = 0;
};

// Largest difference over the common samples: the kite's position (m), the ground tension (N).
Errors errors(const lagrange::Trajectory& run, const lagrange::Trajectory& ref) {
  Errors e;
  for (size_t r = 0; r < std::min(run.rows(), ref.rows()); ++r) {
    double d2 = 0;
    for (const char* c : {"plane.x", "plane.y", "plane.z"}) {
      const double d = run.at(r, c) - ref.at(r, c);
      d2 += d * d;
    }
    e.position = std::max(e.position, std::sqrt(d2));
    e.tension = std::max(
        e.tension, std::abs(run.at(r, "main.tension_ground") - ref.at(r, "main.tension_ground")));
  }
  return e;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lagrange;
  bool quick = false;
  std::string method = IntegratorOptions{}.method;
  for (int i = 1; i < argc; ++i) {
    quick = quick || std::strcmp(argv[i], "--quick") == 0;
    if (std::strcmp(argv[i], "--integrator") == 0 && i + 1 < argc) method = argv[++i];
  }
  const double t_end = quick ? 5.0 : 60.0;
  const bench::Stopwatch clock;
  bench::BuiltModel b = bench::build_model(elastic_kite_yaml(), "<ap2 elastic N=6>");
  const CompiledModel& cm = *b.compiled;
  const auto fly = [&](const std::string& how, double rtol) {
    SimulationOptions so;
    so.output_step = 0.05;
    so.t_end = t_end;
    so.integrator.method = how;
    so.integrator.rtol = rtol;
    so.integrator.atol = rtol * 1e-2;
    const auto s0 = clock.now();
    Trajectory tr = simulate(*b.dynamics, so, cm.q0, cm.v0);
    const double cpu = clock.now().cpu - s0.cpu;
    return std::make_pair(std::move(tr), cpu);
  };
  const auto [ref, ref_cpu] = fly("dop853", 1e-12);
  if (ref.status != Trajectory::Status::Complete) {
    std::fprintf(stderr, "reference run: %s\n", ref.message.c_str());
    return 1;
  }
  std::printf("reference: dop853 at rtol 1e-12, %ld steps, %.2f CPU s\n\n",
              static_cast<long>(ref.stats.steps), ref_cpu);
  std::printf(
      "| integrator | rtol | coordinates | forward call (µs) | steps | %g s flown (CPU s) | "
      "real-time factor (CPU) | kite position error (m) | ground tension error (N) |\n"
      "|---|---|---|---|---|---|---|---|---|\n",
      t_end);
  const double call = bench::forward_call_seconds(b);
  for (double rtol : {1e-3, 1e-6}) {
    const auto [tr, cpu] = fly(method, rtol);
    if (tr.status != Trajectory::Status::Complete) {  // a row that says so, not a number
      std::printf("| %s | %g | %zu | %.2f | %ld | failed at t = %.3f s | | | |\n", method.c_str(),
                  rtol, cm.nq, 1e6 * call, static_cast<long>(tr.stats.steps),
                  tr.rows() ? tr.at(tr.rows() - 1, "t") : 0.0);
      std::fprintf(stderr, "rtol %g: %.300s\n", rtol, tr.message.c_str());
      continue;
    }
    const Errors e = errors(tr, ref);
    std::printf("| %s | %g | %zu | %.2f | %ld | %.3f | %.1f× | %.2e | %.2e |\n", method.c_str(),
                rtol, cm.nq, 1e6 * call, static_cast<long>(tr.stats.steps), cpu, t_end / cpu,
                e.position, e.tension);
    std::fflush(stdout);
  }
  return 0;
}
