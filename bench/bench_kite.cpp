// Kite flight cost (issue 10): the rigid AP2 of examples/rigid_kite_ap2.yaml, its control laws
// unchanged, on an N-segment lumped tether with simple drag, in a logarithmic wind (6 m/s at
// 10 m, z₀ = 0.1 m: 9 m/s at 100 m). Reports, per N: read + derive + compile, the forward-dynamics
// call (KKT solve included), and 60 s of flight with output every 0.05 s at rtol 1e-6,
// atol 1e-8 (as bench_tether), in CPU and wall seconds of this process, with the real-time
// factor; N = 5 (the example's tether) for reference; then t_call(200)/t_call(50). Target:
// N = 50 at ≥ 50× real time on one core. The tapes run as machine code, as `lagrange simulate`
// runs them once its cache holds the model (the compiler run, when not cached, is not counted).
//   bench_kite [--quick] [--all] [--interpreter] [--integrator METHOD]   (--quick: 5 s of
//   flight; --all: also fly N = 200; --interpreter: the tape interpreter instead of machine
//   code; --integrator: another method than the default, to compare in one run)

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_support.hpp"
#include "lagrange/integrator.hpp"
#include "lagrange/simulation.hpp"
#include "tether_models.hpp"

int main(int argc, char** argv) {
  using namespace lagrange;
  bool quick = false, all = false, interpreter = false;
  std::string method = IntegratorOptions{}.method;
  for (int i = 1; i < argc; ++i) {
    quick = quick || std::strcmp(argv[i], "--quick") == 0;
    all = all || std::strcmp(argv[i], "--all") == 0;
    interpreter = interpreter || std::strcmp(argv[i], "--interpreter") == 0;
    if (std::strcmp(argv[i], "--integrator") == 0 && i + 1 < argc) method = argv[++i];
  }
  const double t_end = quick ? 5.0 : 60.0;
  const bench::Stopwatch clock;
  std::map<int, double> call;
  std::string notes;
  std::printf(
      "| N | rtol | coordinates | constraints | read + derive + compile (CPU s) | forward call "
      "(µs) | %g s flown (CPU s) | (wall s) | steps | real-time factor (CPU) |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n",
      t_end);
  struct Case {
    int n;
    double rtol;
    bool fly;
  };
  const std::vector<Case> cases = {{5, 1e-6, true}, {50, 1e-6, true}, {200, 1e-6, all}};
  for (const Case& c : cases) {
    const auto b0 = clock.now();
    bench::BuiltModel b = bench::build_model(bench::kite_yaml(c.n), fmt::format("<ap2 N={}>", c.n));
    const double build = clock.now().cpu - b0.cpu;
    const CompiledModel& cm = *b.compiled;
    notes += fmt::format("N = {}: {}\n", c.n, bench::choose_evaluation(b, interpreter));
    call[c.n] = bench::forward_call_seconds(b);
    if (!c.fly) {
      std::printf("| %d | — | %zu | %zu | %.3f | %.2f | (not flown; --all) | | | |\n", c.n, cm.nq,
                  cm.m, build, 1e6 * call[c.n]);
      continue;
    }
    SimulationOptions so;
    so.output_step = 0.05;
    so.t_end = t_end;
    so.integrator.method = method;
    so.integrator.rtol = c.rtol;
    so.integrator.atol = c.rtol * 1e-2;
    const auto s0 = clock.now();
    const Trajectory tr = simulate(*b.dynamics, so, cm.q0, cm.v0);
    const auto s1 = clock.now();
    if (tr.status != Trajectory::Status::Complete) {
      std::fprintf(stderr, "N = %d: %s\n", c.n, tr.message.c_str());
      return 1;
    }
    const double cpu = s1.cpu - s0.cpu;
    std::printf("| %d | %g | %zu | %zu | %.3f | %.2f | %.2f | %.2f | %ld | %.1f× |\n", c.n, c.rtol,
                cm.nq, cm.m, build, 1e6 * call[c.n], cpu, s1.wall - s0.wall,
                static_cast<long>(tr.stats.steps), t_end / cpu);
    std::fflush(stdout);
  }
  std::printf("\n%s", notes.c_str());
  std::printf("kite_ratio t_call(200)/t_call(50) = %.2f\n", call[200] / call[50]);
  return 0;
}
