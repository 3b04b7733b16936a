// Tether element cost (issue: tethers, wind and winches): a tethered balloon on an N-segment
// lumped tether with simple drag in a logarithmic wind, for N = 10, 50, 100, 200. Reports, in
// CPU seconds of this process: read + derive + compile, the forward-dynamics call (KKT solve
// included), and 60 s of simulation with output every 0.01 s at rtol 1e-6, atol 1e-8, with the
// real-time factor. Targets: t_call(200)/t_call(50) ≤ 5, N = 100 at ≥ 20× real time, derive +
// compile of N = 200 under 2 s. The tapes run as machine code, as `lagrange simulate` runs them
// once its cache holds the model (the compiler run, when not cached, is not counted).
//   bench_tether [--quick] [--interpreter] [--integrator METHOD] [--up-to N]
//   (--interpreter: the tape interpreter instead of machine code; --quick: 5 s of simulation
//   instead of 60, for a smoke run; --integrator: another method than the default, to compare in
//   one run — cvode:jacobian derives the exact Jacobian first, its CPU time printed apart;
//   --up-to: only the sizes up to N; --step-drift TOL: SimulationOptions::step_drift_tol)

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "lagrange/analysis.hpp"
#include "lagrange/integrator.hpp"
#include "lagrange/simulation.hpp"
#include "tether_models.hpp"

int main(int argc, char** argv) {
  using namespace lagrange;
  bool quick = false, interpreter = false;
  int up_to = 200;
  double step_drift = 0.0;
  std::string method = IntegratorOptions{}.method;
  for (int i = 1; i < argc; ++i) {
    quick = quick || std::strcmp(argv[i], "--quick") == 0;
    interpreter = interpreter || std::strcmp(argv[i], "--interpreter") == 0;
    if (std::strcmp(argv[i], "--integrator") == 0 && i + 1 < argc) method = argv[++i];
    if (std::strcmp(argv[i], "--up-to") == 0 && i + 1 < argc) up_to = std::atoi(argv[++i]);
    if (std::strcmp(argv[i], "--step-drift") == 0 && i + 1 < argc)
      step_drift = std::atof(argv[++i]);
  }
  const double t_end = quick ? 5.0 : 60.0;
  const bench::Stopwatch clock;
  std::map<int, double> call;
  std::printf(
      "| N | coordinates | constraints | read + derive + compile (CPU s) | forward call (µs) "
      "| %g s simulated (CPU s) | steps | real-time factor |\n|---|---|---|---|---|---|---|---|\n",
      t_end);
  std::string notes;
  for (int n : {10, 50, 100, 200}) {
    if (n > up_to) break;
    const auto b0 = clock.now();
    bench::BuiltModel b =
        bench::build_model(bench::balloon_yaml(n), fmt::format("<balloon N={}>", n));
    const double build = clock.now().cpu - b0.cpu;
    const CompiledModel& cm = *b.compiled;
    notes += fmt::format("N = {}: {}\n", n, bench::choose_evaluation(b, interpreter));
    call[n] = bench::forward_call_seconds(b);
    SimulationOptions so;
    so.output_step = 0.01;
    so.t_end = t_end;
    so.integrator.method = method;
    so.step_drift_tol = step_drift;
    so.integrator.rtol = 1e-6;
    so.integrator.atol = 1e-8;
    b.dynamics->set_baumgarte(baumgarte_rate(b.model->stabilization, method));
    std::unique_ptr<DynamicsJacobian> jacobian;
    if (method == "cvode:jacobian") {
      const auto j0 = clock.now();
      jacobian = std::make_unique<DynamicsJacobian>(b.equations, b.compiled);
      std::vector<double> y0 = cm.q0;
      y0.insert(y0.end(), cm.v0.begin(), cm.v0.end());
      so.jacobian = ode_jacobian(*jacobian, *b.dynamics, 0.0, y0);
      notes += fmt::format(
          "N = {}: exact Jacobian derived in {:.3f} CPU s, {} non-zeros of {}; ρ·Δt_out = {:.3g}\n",
          n, clock.now().cpu - j0.cpu, so.jacobian.nonzeros(), (cm.nq + cm.nv) * (cm.nq + cm.nv),
          spectral_radius_estimate(so.jacobian, 0.0, y0) * so.output_step);
    }
    const auto s0 = clock.now();
    const Trajectory tr = simulate(*b.dynamics, so, cm.q0, cm.v0);
    const double sim = clock.now().cpu - s0.cpu;
    if (tr.status != Trajectory::Status::Complete) {
      std::fprintf(stderr, "N = %d: %s\n", n, tr.message.c_str());
      return 1;
    }
    std::printf("| %d | %zu | %zu | %.3f | %.2f | %.2f | %ld | %.0f× |\n", n, cm.nq, cm.m, build,
                1e6 * call[n], sim, static_cast<long>(tr.stats.steps), t_end / sim);
    std::fflush(stdout);
  }
  std::printf("\n%s", notes.c_str());
  if (call.count(200))
    std::printf("tether_ratio t_call(200)/t_call(50) = %.2f (target <= 5)\n", call[200] / call[50]);
  return 0;
}
