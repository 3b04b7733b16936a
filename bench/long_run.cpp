// Long run (issue 5): 10⁷ right-hand-side evaluations through the real integrator path
// (simulate → RK4 → Dynamics::forward) must show flat memory. Prints peak RSS after set-up,
// at each of ten output samples, and at the end; exits 1 when it grew by more than 1 MiB.
// Usage: long_run [EVALUATIONS]

#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <memory>

#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/simulation.hpp"
#include "n_link_pendulum.hpp"

namespace {

long peak_rss_kib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;  // KiB on Linux
}

}  // namespace

int main(int argc, char** argv) {
  const double evaluations = argc > 1 ? std::atof(argv[1]) : 1e7;
  const auto model = std::make_unique<lagrange::Model>(
      lagrange::read_model_string(lagrange::bench::cartesian_chain_yaml(3), "chain3"));
  const auto cm = lagrange::compile(lagrange::derive(*model));
  lagrange::Dynamics dyn(cm, cm->parameter_defaults);
  dyn.set_baumgarte(20.0);
  lagrange::SimulationOptions so;
  so.integrator.method = "rk4";
  so.integrator.step = 1e-4;
  so.t_end = evaluations / 4 * so.integrator.step;  // RK4: four evaluations per step
  so.output_step = so.t_end / 10;
  const long start = peak_rss_kib();
  std::printf("long run: %.3g right-hand-side evaluations (3-link Cartesian chain, KKT, RK4)\n",
              evaluations);
  std::printf("  peak RSS after set-up: %ld KiB\n", start);
  so.progress = [](double t) {
    std::printf("  t = %-10.4g peak RSS %ld KiB\n", t, peak_rss_kib());
  };
  const lagrange::Trajectory traj = lagrange::simulate(dyn, so, cm->q0, cm->v0);
  const long end = peak_rss_kib();
  std::printf("  %ld evaluations, status %s; peak RSS at the end: %ld KiB (growth %ld KiB)\n",
              traj.stats.rhs_evals, traj.status_name(), end, end - start);
  return traj.status == lagrange::Trajectory::Status::Complete && end - start <= 1024 ? 0 : 1;
}
