// KPS4-like case of issue 22: the rigid AP2 of examples/rigid_kite_ap2.yaml, its control laws
// unchanged, on a 6-segment *elastic* Dyneema tether (docs/theory.md §4.10) with simple drag in
// a logarithmic wind (6 m/s at 10 m, z₀ = 0.1 m). Line data: d = 2 mm, μ = 4.6 g/m
// (awebox opts/kite_data/ampyx_ap2_settings.py), E = 100 GPa (awebox opts/default.py), so EA = E π
// d²/4 = 314 kN; the damping D = 1000 N·s (on the strain rate) is this benchmark's choice. It flies
// 60 s against a reference run at rtol 1e-12 and reports, per rtol (1e-3, 1e-6), the CPU seconds of
// this process, the real-time factor and the largest error over the output samples (every 0.05 s)
// of the kite's position and the ground tension, for DOP853, cvode:jacobian (BDF on the exact
// sparse Jacobian, docs/theory.md §5.6) and auto, with steps, right-hand sides and Jacobian
// evaluations. KiteModels.jl's KPS4 on 6 segments: 117× (reeling) to 239× (parked), issue 22.
//   bench_elastic_kite [--quick] [--integrator METHOD]   (--quick: 5 s of flight; one method)

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench_support.hpp"
#include "lagrange/analysis.hpp"
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
  std::vector<std::string> methods{"dop853", "cvode:jacobian", "auto"};
  for (int i = 1; i < argc; ++i) {
    quick = quick || std::strcmp(argv[i], "--quick") == 0;
    if (std::strcmp(argv[i], "--integrator") == 0 && i + 1 < argc) methods = {argv[++i]};
  }
  const double t_end = quick ? 5.0 : 60.0;
  const bench::Stopwatch clock;
  bench::BuiltModel b = bench::build_model(elastic_kite_yaml(), "<ap2 elastic N=6>");
  const CompiledModel& cm = *b.compiled;
  // The exact Jacobian (docs/theory.md §5.6) for cvode:jacobian and auto, its evaluations counted.
  const auto j0 = clock.now();
  const DynamicsJacobian derivatives(b.equations, b.compiled);
  std::vector<double> y0 = cm.q0;
  y0.insert(y0.end(), cm.v0.begin(), cm.v0.end());
  OdeJacobian jacobian = ode_jacobian(derivatives, *b.dynamics, 0.0, y0);
  const double derive_cpu = clock.now().cpu - j0.cpu;
  long jacobian_evals = 0;
  const auto values = jacobian.values;
  jacobian.values = [&](double t, const double* y, double* out) {
    ++jacobian_evals;
    values(t, y, out);
  };
  const auto fly = [&](const std::string& how, double rtol) {
    SimulationOptions so;
    so.output_step = 0.05;
    so.t_end = t_end;
    so.integrator.method = how;
    so.integrator.rtol = rtol;
    so.integrator.atol = rtol * 1e-2;
    if (how != "dop853") so.jacobian = jacobian;
    b.dynamics->set_baumgarte(baumgarte_rate(b.model->stabilization, how));
    jacobian_evals = 0;
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
  std::printf("reference: dop853 at rtol 1e-12, %ld steps, %.2f CPU s\n",
              static_cast<long>(ref.stats.steps), ref_cpu);
  std::printf(
      "exact Jacobian: derived and its pattern probed in %.3f CPU s, %zu non-zeros of %zu\n",
      derive_cpu, jacobian.nonzeros(), y0.size() * y0.size());
  const double call = bench::forward_call_seconds(b);
  {  // one evaluation of the exact Jacobian in flight (the reference at t = 1 s, the line taut),
     // averaged over at least 0.3 s of calls
    std::vector<double> y, out(jacobian.nonzeros());
    for (const auto* names : {&cm.coordinate_names, &cm.velocity_names})
      for (const std::string& name : *names) y.push_back(ref.at(20, name));
    long calls = 0;
    const auto c0 = clock.now();
    do {
      values(1.0, y.data(), out.data());
      ++calls;
    } while (clock.now().cpu - c0.cpu < 0.3);
    std::printf("exact Jacobian evaluation: %.1f µs (forward call %.2f µs)\n\n",
                1e6 * (clock.now().cpu - c0.cpu) / static_cast<double>(calls), 1e6 * call);
  }
  std::printf(
      "| integrator | rtol | forward call (µs) | steps | rhs evaluations | Jacobian evaluations | "
      "%g s flown (CPU s) | real-time factor (CPU) | kite position error (m) | ground tension "
      "error (N) |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n",
      t_end);
  for (double rtol : {1e-3, 1e-6})
    for (const std::string& method : methods) {
      const auto [tr, cpu] = fly(method, rtol);
      const std::string ran = tr.stats.method.empty() ? method : tr.stats.method;
      if (tr.status != Trajectory::Status::Complete) {  // a row that says so, not a number
        std::printf("| %s | %g | %.2f | %ld | %ld | %ld | failed at t = %.3f s | | | |\n",
                    ran.c_str(), rtol, 1e6 * call, static_cast<long>(tr.stats.steps),
                    static_cast<long>(tr.stats.rhs_evals), jacobian_evals,
                    tr.rows() ? tr.at(tr.rows() - 1, "t") : 0.0);
        std::fprintf(stderr, "%s, rtol %g: %.300s\n", method.c_str(), rtol, tr.message.c_str());
        continue;
      }
      const Errors e = errors(tr, ref);
      std::printf("| %s | %g | %.2f | %ld | %ld | %ld | %.3f | %.1f× | %.2e | %.2e |\n",
                  ran.c_str(), rtol, 1e6 * call, static_cast<long>(tr.stats.steps),
                  static_cast<long>(tr.stats.rhs_evals), jacobian_evals, cpu, t_end / cpu,
                  e.position, e.tension);
      std::fflush(stdout);
    }
  return 0;
}
