// KPS4-like cases of issue 22: the rigid AP2 of examples/rigid_kite_ap2.yaml on a 6-segment
// *elastic* Dyneema tether (docs/theory.md §4.10), flown three ways, each against a reference run
// at rtol 1e-12 (DOP853). Per rtol (1e-3, 1e-6; atol = rtol·1e-2) and integrator (DOP853,
// cvode:jacobian and ida:jacobian on the exact sparse Jacobian, docs/theory.md §5.6, and auto)
// it reports the CPU seconds of this process (short runs: the mean of repeats), the real-time
// factor, steps, right-hand sides, Jacobian evaluations and the largest error over the output
// samples (every 0.05 s) of the kite's position and the ground tension; for the peer's cases
// also the BDF methods at the peer's tolerances (rtol 1e-3, atol 6e-4, order ≤ 4).
//  figure-eight: its control laws unchanged, 200 m of 2 mm line, μ = 4.6 g/m (awebox
//    opts/kite_data/ampyx_ap2_settings.py), E = 100 GPa (awebox opts/default.py), EA = E π d²/4
//    = 314 kN, damping D = 1000 N·s (this benchmark's choice), logarithmic wind 6 m/s at 10 m,
//    60 s from the file's crosswind start.
//  parked and reeling: KiteModels.jl's bench.jl and bench_4p.jl (ufechner7/KiteModels.jl
//    d3cc775, examples/, data/settings.yaml): 150 m of their 4 mm Dyneema in 6 segments,
//    c_spring = EA = 614.6 kN, damping 473 N·s, ρ = 724 kg/m³ (μ = 9.10 g/m), logarithmic wind
//    from their reference height 6 m and roughness 2e-4 m. Their KPS4 (14.6 kg with the KCU, 10.2
//    m²) parks in their 9.51 m/s; for the AP2 (36.8 kg, 3 m²) `lagrange trim` finds no
//    equilibrium there (nor at 13 m/s; one at 14), so it flies in 15 m/s at 6 m (19.5 m/s at the
//    kite), on the three-line bridle of examples/bridled_kite.yaml. No steering: the elevator
//    holds α, the ailerons keep the span tangent to the tether sphere, the rudder damps
//    sideslip. As the peer, 5 s of warm-up untimed, from a start near the equilibrium; then
//    parked: 25 s at constant length (the peer's timed 500 control steps of 0.05 s); reeling: 5 s
//    with the reel-out speed rising at 0.1 m/s² from rest (their 100 timed steps), length
//    150 + 0.05 t² m.
// KiteModels.jl's KPS4, DFBDF at rtol 1e-3 on a Ryzen 7950X: 239× parked, 117× reeling.
//   bench_elastic_kite [--quick] [--integrator METHOD] [--case figure-eight|parked|reeling]
//   (--quick: 5 s of the figure-eight; one method; one case)

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

#include "support/test_paths.hpp"
#include "bench_support.hpp"
#include "lagrange/analysis.hpp"
#include "lagrange/integrator.hpp"
#include "lagrange/simulation.hpp"

namespace {

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("the example lacks " + from);
  return text.replace(at, from.size(), to);
}

// examples/<file> with 6 tether segments instead of 5.
std::string ap2_yaml(const std::string& file) {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/examples/" + file);
  std::stringstream ss;
  ss << in.rdbuf();
  return replaced(ss.str(), "segments: 5", "segments: 6");
}

// The figure-eight: the file's control laws and start, the line elastic, the wind logarithmic.
std::string figure_eight_yaml() {
  std::string text = replaced(ap2_yaml("rigid_kite_ap2.yaml"), "drag: simple}",
                              "drag: simple, elasticity: {EA: 314159, damping: 1000}}");
  return replaced(text, "wind: {speed: W}",
                  "wind: {profile: logarithmic, speed: W, reference_height: 10, roughness: 0.1}");
}

// examples/bridled_kite.yaml (the line on a bridle's knot, which a line of varying length
// needs) with KiteModels.jl's line and wind (header), no steering; `length`: the free length in m.
std::string parked_yaml(const std::string& length) {
  std::string text = replaced(ap2_yaml("bridled_kite.yaml"), "  W: 6\n", "  W: 15\n");
  text = replaced(text, "wind: {speed: W}",
                  "wind: {profile: logarithmic, speed: W, reference_height: 6, roughness: 0.0002}");
  text =
      replaced(text, "segments: 6, length: 199.5, mass_per_length: 0.0046, diameter: 0.002",
               "segments: 6, length: " + length + ", mass_per_length: 0.009098, diameter: 0.004");
  text = replaced(text, "drag: simple}", "drag: simple, elasticity: {EA: 614600, damping: 473}}");
  // near the equilibrium: nose into the wind, wing level, at rest
  text = replaced(text, "position: [173.20508075688772, 0, 100]", "position: [51.3, 0, 141]");
  text =
      replaced(text, "[[0, 0.5, -0.8660254037844386], [1, 0, 0], [0, -0.8660254037844386, -0.5]]",
               "[[-1, 0, 0], [0, 1, 0], [0, 0, -1]]");
  text = replaced(text, "velocity: [0, 40, 0]", "velocity: [0, 0, 0]");
  const size_t aileron = text.find("    aileron: >-");
  if (aileron == std::string::npos) throw std::runtime_error("bridled_kite.yaml lacks aileron");
  return text.substr(0, aileron) +
         "    aileron: -k_roll*asin(dot(plane.R*[0, 1, 0], plane.r)/norm(plane.r))\n";
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

struct Case {
  std::string name, yaml;
  double t_end;
  /// > 0: start from the parked kite's state after this many seconds (untimed, as the peer's
  /// warm-up), else from the file's state
  double warm_up;
};

// The parked kite's state (q, v) after `seconds` from its file's start near the equilibrium
// (straight line, level wing), flown at rtol 1e-10; q and v are of the parked and reeling models
// alike (the same coordinates).
void settle(double seconds, std::vector<double>& q, std::vector<double>& v) {
  using namespace lagrange;
  bench::BuiltModel b = bench::build_model(parked_yaml("150"), "<ap2 elastic N=6, warm-up>");
  SimulationOptions so;
  so.output_step = seconds;
  so.t_end = seconds;
  so.integrator.method = "dop853";
  so.integrator.rtol = 1e-10;
  so.integrator.atol = 1e-12;
  b.dynamics->set_baumgarte(baumgarte_rate(b.model->stabilization, "dop853"));
  const Trajectory tr = simulate(*b.dynamics, so, b.compiled->q0, b.compiled->v0);
  if (tr.status != Trajectory::Status::Complete) throw std::runtime_error("warm-up: " + tr.message);
  const size_t last = tr.rows() - 1;
  q.clear();
  v.clear();
  for (const std::string& name : b.compiled->coordinate_names) q.push_back(tr.at(last, name));
  for (const std::string& name : b.compiled->velocity_names) v.push_back(tr.at(last, name));
  std::printf("warm-up: %g s, kite at (%.2f, %.2f, %.2f) m, ground tension %.0f N\n", seconds,
              tr.at(last, "plane.x"), tr.at(last, "plane.y"), tr.at(last, "plane.z"),
              tr.at(last, "main.tension_ground"));
}

// Flies one case with `methods` at rtol 1e-3 and 1e-6 and prints its table.
int run_case(const Case& c, const std::vector<std::string>& methods) {
  using namespace lagrange;
  const bench::Stopwatch clock;
  bench::BuiltModel b = bench::build_model(c.yaml, "<ap2 elastic N=6, " + c.name + ">");
  const CompiledModel& cm = *b.compiled;
  // The exact Jacobian (docs/theory.md §5.6) for cvode:jacobian, ida:jacobian and auto, its
  // evaluations counted.
  const auto j0 = clock.now();
  const DynamicsJacobian derivatives(b.equations, b.compiled);
  std::vector<double> q0 = cm.q0, v0 = cm.v0;
  if (c.warm_up > 0) settle(c.warm_up, q0, v0);
  std::vector<double> y0 = q0;
  y0.insert(y0.end(), v0.begin(), v0.end());
  OdeJacobian jacobian = ode_jacobian(derivatives, *b.dynamics, 0.0, y0);
  const double derive_cpu = clock.now().cpu - j0.cpu;
  long jacobian_evals = 0;
  const auto values = jacobian.values;
  jacobian.values = [&](double t, const double* y, double* out) {
    ++jacobian_evals;
    values(t, y, out);
  };
  JacobianSource dae_source;
  dae_source.dae = [&](Dynamics& dyn, double t0, const std::vector<double>& y) {
    DaeJacobian out = dae_jacobian(derivatives, dyn, t0, y);
    out.values = [&jacobian_evals, f = std::move(out.values)](double t, double cj, const double* x,
                                                              const double* xp, double* v) {
      ++jacobian_evals;
      f(t, cj, x, xp, v);
    };
    return out;
  };
  const auto fly = [&](const std::string& how, double rtol, double atol = 0, int max_order = 5) {
    SimulationOptions so;
    so.output_step = 0.05;
    so.t_end = c.t_end;
    so.integrator.method = how;
    so.integrator.rtol = rtol;
    so.integrator.atol = atol > 0 ? atol : rtol * 1e-2;
    so.integrator.max_order = max_order;
    if (how == "ida:jacobian")
      so.jacobian_source = dae_source;
    else if (how != "dop853")
      so.jacobian = jacobian;
    b.dynamics->set_baumgarte(baumgarte_rate(b.model->stabilization, how));
    // short runs repeated until 0.3 CPU s have passed: the mean (the runs are identical)
    Trajectory tr;
    int runs = 0;
    const auto s0 = clock.now();
    do {
      jacobian_evals = 0;
      tr = simulate(*b.dynamics, so, q0, v0);
      ++runs;
    } while (clock.now().cpu - s0.cpu < 0.3 && rtol > 1e-10);
    const double cpu = (clock.now().cpu - s0.cpu) / runs;
    return std::make_pair(std::move(tr), cpu);
  };
  const auto [ref, ref_cpu] = fly("dop853", 1e-12);
  if (ref.status != Trajectory::Status::Complete) {
    std::fprintf(stderr, "%s, reference run: %s\n", c.name.c_str(), ref.message.c_str());
    return 1;
  }
  std::printf("%s: reference dop853 at rtol 1e-12, %ld steps, %.2f CPU s\n", c.name.c_str(),
              static_cast<long>(ref.stats.steps), ref_cpu);
  std::printf(
      "exact Jacobian: derived and its pattern probed in %.3f CPU s, %zu non-zeros of %zu\n",
      derive_cpu, jacobian.nonzeros(), y0.size() * y0.size());
  const double call = bench::forward_call_seconds(b);
  {  // one evaluation of the exact Jacobian in flight (the reference at t = 1 s), averaged over
     // at least 0.3 s of calls
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
      "| integrator | rtol | steps | rhs evaluations | Jacobian evaluations | "
      "%g s flown (CPU s) | real-time factor (CPU) | kite position error (m) | ground tension "
      "error (N) |\n"
      "|---|---|---|---|---|---|---|---|---|\n",
      c.t_end);
  // Our tolerances (atol = rtol·1e-2, BDF order ≤ 5) for every method, and for the peer's cases
  // KiteModels' own (data/settings.yaml: abs_tol 6e-4, max_order 4) for the BDF methods.
  struct Setting {
    double rtol, atol;
    int max_order;
    bool bdf_only;
  };
  std::vector<Setting> settings{{1e-3, 1e-5, 5, false}, {1e-6, 1e-8, 5, false}};
  if (c.warm_up > 0) settings.insert(settings.begin() + 1, {1e-3, 6e-4, 4, true});
  for (const Setting& set : settings)
    for (const std::string& method : methods) {
      if (set.bdf_only && method != "cvode:jacobian" && method != "ida:jacobian") continue;
      const auto [tr, cpu] = fly(method, set.rtol, set.atol, set.max_order);
      const std::string ran = tr.stats.method.empty() ? method : tr.stats.method;
      const std::string tol = set.max_order < 5 ? fmt::format("{:g}, atol {:g}, order ≤ {}",
                                                              set.rtol, set.atol, set.max_order)
                                                : fmt::format("{:g}", set.rtol);
      if (tr.status != Trajectory::Status::Complete) {  // a row that says so, not a number
        std::printf("| %s | %s | %ld | %ld | %ld | failed at t = %.3f s | | | |\n", ran.c_str(),
                    tol.c_str(), static_cast<long>(tr.stats.steps),
                    static_cast<long>(tr.stats.rhs_evals), jacobian_evals,
                    tr.rows() ? tr.at(tr.rows() - 1, "t") : 0.0);
        std::fprintf(stderr, "%s, %s: %.300s\n", method.c_str(), tol.c_str(), tr.message.c_str());
        continue;
      }
      const Errors e = errors(tr, ref);
      std::printf("| %s | %s | %ld | %ld | %ld | %.3f | %.1f× | %.2e | %.2e |\n", ran.c_str(),
                  tol.c_str(), static_cast<long>(tr.stats.steps),
                  static_cast<long>(tr.stats.rhs_evals), jacobian_evals, cpu, c.t_end / cpu,
                  e.position, e.tension);
      std::fflush(stdout);
    }
  std::printf("\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string only;
  std::vector<std::string> methods{"dop853", "cvode:jacobian", "ida:jacobian", "auto"};
  for (int i = 1; i < argc; ++i) {
    quick = quick || std::strcmp(argv[i], "--quick") == 0;
    if (std::strcmp(argv[i], "--integrator") == 0 && i + 1 < argc) methods = {argv[++i]};
    if (std::strcmp(argv[i], "--case") == 0 && i + 1 < argc) only = argv[++i];
  }
  const std::vector<Case> cases{{"figure-eight", figure_eight_yaml(), quick ? 5.0 : 60.0, 0.0},
                                {"parked", parked_yaml("150"), 25.0, 5.0},
                                {"reeling", parked_yaml("150 + 0.05*t^2"), 5.0, 5.0}};
  bool known = only.empty();
  for (const Case& c : cases) {
    if (!only.empty() && c.name != only) continue;
    known = true;
    if (run_case(c, methods) != 0) return 1;
  }
  if (!known) {
    std::fprintf(stderr, "--case %s: expected figure-eight, parked or reeling\n", only.c_str());
    return 2;
  }
  return 0;
}
