// Work–precision (docs/benchmarks.md, "Work–precision"): for each model and each method, runs
// at rtol 1e-4 … 1e-10 (atol = rtol / 100) and prints one JSON line per run: the largest error of
// the coordinates over the samples (every 0.1 s) against a reference run at rtol 1e-13 with
// arkode:verner65, right-hand-side evaluations, steps, wall and CPU seconds of simulate().
//   work_precision OUT_DIR [MODEL ...]  also writes OUT_DIR/reference_<model>.json (t and q per
//                              sample), which bench/work_precision.py scores the SciPy peers
//                              against; with MODEL names, runs only those models; with
//                              LAGRANGE_WP_METHODS=m1,m2,… in the environment, only those methods.

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "support/test_paths.hpp"
#include "bench_support.hpp"
#include "lagrange/simulation.hpp"
#include "n_link_pendulum.hpp"

namespace {

using lagrange::bench::BuiltModel;
using lagrange::bench::Stopwatch;

struct Case {
  std::string name;
  std::string yaml;
  double t_end;
  lagrange::Formulation form = lagrange::Formulation::Lagrangian;
};

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string example(const std::string& name) {
  return read_file(std::string(LAGRANGE_SOURCE_DIR) + "/examples/" + name);
}

/// The coordinates q at every sample, row by row.
std::vector<double> coordinates(const lagrange::Trajectory& tr, size_t nq) {
  std::vector<double> q;
  for (size_t r = 0; r < tr.rows(); ++r)
    for (size_t i = 0; i < nq; ++i) q.push_back(tr.data[r * tr.columns.size() + 1 + i]);
  return q;
}

struct Run {
  lagrange::Trajectory trajectory;
  double wall = 0.0, cpu = 0.0;
};

/// One run of `method`; its wall and CPU time are the least of up to three repetitions (one when
/// a run takes over a second), so that a stray pause of the machine does not count.
Run run(BuiltModel& b, const Case& c, const std::string& method, double rtol) {
  lagrange::SimulationOptions so;
  so.t_end = c.t_end;
  so.output_step = 0.1;
  so.integrator.method = method;
  so.integrator.rtol = rtol;
  so.integrator.atol = rtol / 100.0;
  so.integrator.max_steps = 100000000;
  const Stopwatch clock;
  Run r;
  r.wall = r.cpu = HUGE_VAL;
  for (int repeat = 0; repeat < 3; ++repeat) {
    const auto start = clock.now();
    r.trajectory = lagrange::simulate(*b.dynamics, so, b.compiled->q0, b.compiled->v0);
    const auto end = clock.now();
    r.wall = std::min(r.wall, end.wall - start.wall);
    r.cpu = std::min(r.cpu, end.cpu - start.cpu);
    if (r.wall > 1.0) break;
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out_dir = argc > 1 ? argv[1] : ".";
  const std::vector<Case> cases{
      {"double_pendulum", example("double_pendulum.yaml"), 10.0},
      {"chain_10", lagrange::bench::n_link_pendulum_yaml(10), 5.0},
      {"chain_50", lagrange::bench::n_link_pendulum_yaml(50), 1.0},
      {"tumbling_brick", example("tumbling_brick.yaml"), 10.0},
      {"five_bar", example("five_bar.yaml"), 5.0},
      {"cartesian_chain_10", lagrange::bench::cartesian_chain_yaml(10), 5.0},
      // The pendulum chain as `links:` on the recursive formulation (docs/theory.md §4.9).
      {"links_chain_100", lagrange::bench::links_chain_yaml(100), 1.0,
       lagrange::Formulation::Recursive},
      {"links_chain_200", lagrange::bench::links_chain_yaml(200), 1.0,
       lagrange::Formulation::Recursive},
  };
  // Optional model names after the output directory run only those cases.
  const std::vector<std::string> only(argv + std::min(argc, 2), argv + argc);
  std::vector<std::string> methods{"arkode",
                                   "dop853",
                                   "arkode:dormand-prince",
                                   "arkode:verner65",
                                   "arkode:verner87",
                                   "arkode:fehlberg78",
                                   "arkode:zonneveld",
                                   "cvode"};
  // LAGRANGE_WP_METHODS=a,b,... runs only those methods (the reference run is always made).
  if (const char* chosen = std::getenv("LAGRANGE_WP_METHODS")) {
    std::vector<std::string> kept;
    std::string list = chosen;
    for (size_t start = 0, end = 0; start <= list.size(); start = end + 1) {
      end = std::min(list.find(',', start), list.size());
      if (end > start) kept.push_back(list.substr(start, end - start));
    }
    methods = kept;
  }
  for (const Case& c : cases) {
    if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
    BuiltModel b = lagrange::bench::build_model(c.yaml, c.name, c.form);
    // Machine code, as `lagrange simulate` runs once its cache holds the model.
    b.dynamics->set_evaluation(lagrange::Evaluation::MachineCode);
    fmt::print(stderr, "{}: {}\n", c.name, b.dynamics->evaluation_note());
    const size_t nq = b.compiled->nq;
    const Run reference = run(b, c, "arkode:verner65", 1e-13);
    if (reference.trajectory.status != lagrange::Trajectory::Status::Complete) {
      fmt::print(stderr, "{}: reference run failed: {}\n", c.name, reference.trajectory.message);
      return 1;
    }
    const std::vector<double> q_ref = coordinates(reference.trajectory, nq);
    {
      std::ofstream ref(out_dir + "/reference_" + c.name + ".json");
      ref << fmt::format("{{\"model\": \"{}\", \"t_end\": {}, \"nq\": {}, \"q\": [{:.17g}]}}\n",
                         c.name, c.t_end, nq, fmt::join(q_ref, ", "));
    }
    for (const std::string& method : methods) {
      for (int e = 4; e <= 10; ++e) {
        const double rtol = std::pow(10.0, -e);
        const Run r = run(b, c, method, rtol);
        const std::vector<double> q = coordinates(r.trajectory, nq);
        double error = HUGE_VAL;
        if (r.trajectory.status == lagrange::Trajectory::Status::Complete &&
            q.size() == q_ref.size()) {
          error = 0.0;
          for (size_t i = 0; i < q.size(); ++i) error = std::max(error, std::abs(q[i] - q_ref[i]));
        }
        fmt::print(
            "{{\"engine\": \"lagrange\", \"model\": \"{}\", \"method\": \"{}\", \"ran\": \"{}\", "
            "\"rtol\": {:g}, \"error\": {:.3e}, \"rhs_evals\": {}, \"steps\": {}, "
            "\"wall_s\": {:.6f}, \"cpu_s\": {:.6f}}}\n",
            c.name, method, r.trajectory.stats.method, rtol, error, r.trajectory.stats.rhs_evals,
            r.trajectory.stats.steps, r.wall, r.cpu);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}
