// Work–precision of the implicit methods on exact Jacobians (issue 22 item 3, docs/benchmarks.md
// "IDA on the exact sparse Jacobian"): the 100-segment tethered balloon, the rigid AP2 on 50
// segments and the AP2 on a 6-segment elastic Dyneema tether (the KPS4-like case of
// bench_elastic_kite). Per model a reference run (DOP853, rtol 1e-12), then dop853,
// cvode:jacobian and ida:jacobian at rtol 1e-3, 1e-4, 1e-6 (atol = rtol / 100): CPU seconds of
// simulate() in this process, real-time factor, steps, and the largest error of any coordinate
// over the samples against the reference. Then ida:jacobian's (and DOP853's) cost per simulated
// second of the balloon at rtol 1e-6 for N = 10 … 200.
//   bench_implicit [--t-end T] [--model balloon|kite|elastic] [--no-scaling] [--step-drift TOL]
//                  [--methods m1,m2]
//   (T: seconds flown, 10 by default; --model: only that model; TOL: step_drift_tol;
//   --methods: only those, comma-separated)

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "lagrange/analysis.hpp"
#include "lagrange/simulation.hpp"
#include "tether_models.hpp"

namespace {

using namespace lagrange;

double step_drift = 0.0;  // SimulationOptions::step_drift_tol (--step-drift)
std::string methods = "dop853,cvode:jacobian,ida:jacobian";  // --methods

// The elastic KPS4-like kite of bench_elastic_kite.cpp (EA = 314 kN, D = 1000 N·s).
std::string elastic_kite_yaml() {
  std::string text = bench::kite_yaml(6);
  return bench::replaced(text, "drag: simple}",
                         "drag: simple, elasticity: {EA: 314159, damping: 1000}}");
}

struct Run {
  Trajectory tr;
  double cpu = 0.0;
};

// One run of `method` with the exact Jacobians derived once (`jac`), as the CLI hands them.
Run fly(bench::BuiltModel& b, const DynamicsJacobian& jac, const std::string& method, double rtol,
        double t_end, double output_step) {
  SimulationOptions so;
  so.t_end = t_end;
  so.output_step = output_step;
  so.integrator.method = method;
  so.integrator.rtol = rtol;
  so.integrator.atol = rtol * 1e-2;
  so.step_drift_tol = step_drift;
  so.jacobian_source.ode = [&jac](Dynamics& d, double t0, const std::vector<double>& y0) {
    return ode_jacobian(jac, d, t0, y0);
  };
  so.jacobian_source.dae = [&jac](Dynamics& d, double t0, const std::vector<double>& y0) {
    return dae_jacobian(jac, d, t0, y0);
  };
  b.dynamics->set_baumgarte(baumgarte_rate(b.model->stabilization, method));
  const bench::Stopwatch clock;
  const auto s0 = clock.now();
  Run run{simulate(*b.dynamics, so, b.compiled->q0, b.compiled->v0), 0.0};
  run.cpu = clock.now().cpu - s0.cpu;
  return run;
}

// Largest difference of any coordinate over the common samples.
double error(const Trajectory& run, const Trajectory& ref, const CompiledModel& cm) {
  double e = 0.0;
  for (size_t r = 0; r < std::min(run.rows(), ref.rows()); ++r)
    for (const std::string& name : cm.coordinate_names)
      e = std::max(e, std::abs(run.at(r, name) - ref.at(r, name)));
  return e;
}

void work_precision(const std::string& label, const std::string& yaml, double t_end,
                    double output_step) {
  bench::BuiltModel b = bench::build_model(yaml, label);
  const bench::Stopwatch clock;
  const auto j0 = clock.now();
  const DynamicsJacobian jac(b.equations, b.compiled);
  const double derive = clock.now().cpu - j0.cpu;
  std::vector<double> y0 = b.compiled->q0;
  y0.insert(y0.end(), b.compiled->v0.begin(), b.compiled->v0.end());
  const size_t n = y0.size(), size = n + b.compiled->m;
  std::printf("\n%s: Newton matrix non-zeros: ida:jacobian %zu of %zu², cvode:jacobian %zu of %zu²",
              label.c_str(), dae_jacobian(jac, *b.dynamics, 0.0, y0).nonzeros(), size,
              ode_jacobian(jac, *b.dynamics, 0.0, y0).nonzeros(), n);
  const Run ref = fly(b, jac, "dop853", 1e-12, t_end, output_step);
  if (ref.tr.status != Trajectory::Status::Complete) {
    std::fprintf(stderr, "%s reference: %s\n", label.c_str(), ref.tr.message.c_str());
    return;
  }
  const CompiledModel& cm = *b.compiled;
  std::printf(
      "\n%s: nq = %zu, m = %zu, %g s flown, output every %g s; exact Jacobian derived in %.2f "
      "CPU s; reference dop853 rtol 1e-12: %ld steps, %.2f CPU s\n\n"
      "| integrator | rtol | steps | failed | evaluations | CPU s | real-time factor | largest "
      "coordinate error |\n|---|---|---|---|---|---|---|---|\n",
      label.c_str(), cm.nq, cm.m, t_end, output_step, derive, static_cast<long>(ref.tr.stats.steps),
      ref.cpu);
  for (double rtol : {1e-3, 1e-4, 1e-6})
    for (const std::string& method : {"dop853", "cvode:jacobian", "ida:jacobian"}) {
      if (methods.find(method) == std::string::npos) continue;
      const Run run = fly(b, jac, method, rtol, t_end, output_step);
      if (run.tr.status != Trajectory::Status::Complete) {
        std::printf("| %s | %g | %ld | | | failed at t = %.3f: %.120s | | |\n", method.c_str(),
                    rtol, static_cast<long>(run.tr.stats.steps), run.tr.failure_time,
                    run.tr.message.c_str());
        continue;
      }
      std::printf("| %s | %g | %ld | %ld | %ld | %.3f | %.1f× | %.1e |\n", method.c_str(), rtol,
                  static_cast<long>(run.tr.stats.steps),
                  static_cast<long>(run.tr.stats.failed_steps),
                  static_cast<long>(run.tr.stats.rhs_evals), run.cpu, t_end / run.cpu,
                  error(run.tr, ref.tr, cm));
      std::fflush(stdout);
    }
}

}  // namespace

int main(int argc, char** argv) {
  double t_end = 10.0;
  std::string only;
  bool scaling = true;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--t-end") == 0 && i + 1 < argc) t_end = std::atof(argv[++i]);
    if (std::strcmp(argv[i], "--model") == 0 && i + 1 < argc) only = argv[++i];
    if (std::strcmp(argv[i], "--no-scaling") == 0) scaling = false;
    if (std::strcmp(argv[i], "--step-drift") == 0 && i + 1 < argc)
      step_drift = std::atof(argv[++i]);
    if (std::strcmp(argv[i], "--methods") == 0 && i + 1 < argc) methods = argv[++i];
  }
  if (only.empty() || only == "balloon")
    work_precision("balloon N = 100", bench::balloon_yaml(100), t_end, 0.01);
  if (only.empty() || only == "kite")
    work_precision("rigid AP2 N = 50", bench::kite_yaml(50), t_end, 0.05);
  if (only.empty() || only == "elastic")
    work_precision("AP2 on 6 elastic segments", elastic_kite_yaml(), t_end, 0.05);
  if (!scaling) return 0;
  std::printf(
      "\nballoon, rtol 1e-6, %g s: CPU seconds per simulated second against N\n\n"
      "| N | dop853 | ida:jacobian | ida:jacobian steps |\n|---|---|---|---|\n",
      t_end);
  for (int n : {10, 25, 50, 100, 200}) {
    bench::BuiltModel b = bench::build_model(bench::balloon_yaml(n), fmt::format("<N={}>", n));
    const DynamicsJacobian jac(b.equations, b.compiled);
    const Run explicit_run = fly(b, jac, "dop853", 1e-6, t_end, 0.01);
    const Run implicit_run = fly(b, jac, "ida:jacobian", 1e-6, t_end, 0.01);
    std::printf("| %d | %.4f | %.4f | %ld |\n", n, explicit_run.cpu / t_end,
                implicit_run.cpu / t_end, static_cast<long>(implicit_run.tr.stats.steps));
    std::fflush(stdout);
  }
  return 0;
}
