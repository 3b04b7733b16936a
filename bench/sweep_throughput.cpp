// Study throughput (issue 24, docs/sweeps.md): cases per second of a parameter sweep with 1 and
// 2 workers on one compiled model, the parallel efficiency, the time spent deriving once against
// running, and the per-case overhead of the pool and the summary (wall time not inside a case).
//
//   sweep_throughput [CASES_PENDULUM=1000] [CASES_KITE=100]

#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "support/test_paths.hpp"
#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/sweep.hpp"

namespace {

using namespace lagrange;
using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// One model: derive once, read each case's values, run the cases with 1 and then 2 workers.
void study(const std::string& file, const std::string& parameter, double low, double high,
           size_t cases, double t_end) {
  const std::string path = std::string(LAGRANGE_SOURCE_DIR) + "/examples/" + file;
  const auto t0 = Clock::now();
  const Model base = read_model_file(path);
  const Formulation form =
      recursive_unsuitable(base).empty() ? Formulation::Recursive : Formulation::Lagrangian;
  const auto compiled = compile(derive(base, form));
  const double derive_seconds = since(t0);
  const auto axis = sweep::parse_axis(fmt::format("{}={}:{}:{}", parameter, low, high, cases));
  const auto options_of = [&](const Model& m) {
    SimulationOptions so;
    so.t_end = t_end;
    so.output_step = m.simulate.output_step;
    so.integrator.method = m.simulate.integrator;
    so.integrator.rtol = m.simulate.rtol;
    so.integrator.atol = m.simulate.atol;
    so.integrator.step = m.simulate.step;
    so.project = m.stabilization.project;
    return so;
  };
  const std::vector<sweep::Case> grid = sweep::make_cases({axis}, {}, 0, 1);
  const auto t1 = Clock::now();
  std::vector<sweep::CaseInput> inputs;
  for (const auto& c : grid) {
    const Model m = read_model_file(path, {{c.values[0].first, c.values[0].second}});
    inputs.push_back(sweep::case_input(m, *compiled, options_of(m)));
  }
  const double read_seconds = since(t1);
  // The same inputs from one traced read (as `lagrange sweep` makes them, docs/theory.md §9.4).
  const auto t3 = Clock::now();
  ReadTrace trace;
  trace.watched = {parameter};
  const Model traced = read_model_file(path, {grid[0].values[0]}, trace);
  if (!trace.opaque.empty()) throw std::runtime_error(file + ": not replayable: " + trace.opaque);
  const sweep::ReplayedInputs replay(traced, trace,
                                     sweep::case_input(traced, *compiled, options_of(traced)));
  const double trace_seconds = since(t3);
  const auto t4 = Clock::now();
  for (size_t i = 0; i < grid.size(); ++i) {
    const std::optional<sweep::CaseInput> in = replay(grid[i].values);
    if (!in || in->q0 != inputs[i].q0 || in->v0 != inputs[i].v0 ||
        in->parameters != inputs[i].parameters)
      throw std::runtime_error(file + ": the replayed inputs differ from the read ones");
  }
  const double replay_seconds = since(t4);
  std::vector<sweep::Metric> metrics{sweep::parse_metric("max(energy)")};
  sweep::bind_metrics(metrics, trajectory_columns(*compiled), compiled->parameter_names);
  std::vector<size_t> pending(inputs.size());
  for (size_t i = 0; i < pending.size(); ++i) pending[i] = i;
  const std::string summary_path =
      (std::filesystem::temp_directory_path() / fmt::format("sweep-bench-{}.csv", getpid()))
          .string();
  double rate1 = 0;
  fmt::print(
      "{} ({} cases of {} s, {} from {} to {}): derive + compile once {:.3f} s, read the "
      "cases' values {:.3f} s ({:.2f} ms/case), or one traced read {:.3f} s and the cases' "
      "inputs from it {:.4f} ms/case\n",
      file, cases, t_end, parameter, low, high, derive_seconds, read_seconds,
      1e3 * read_seconds / static_cast<double>(cases), trace_seconds,
      1e3 * replay_seconds / static_cast<double>(cases));
  for (const size_t workers : {1, 2}) {
    std::filesystem::remove(summary_path);
    sweep::SummaryFile summary(summary_path, {"case", parameter, "status", "max_energy", "wall_s"},
                               false);
    double in_cases = 0;
    sweep::PoolOptions pool;
    pool.workers = workers;
    pool.evaluation = Evaluation::SharedMachineCode;  // as `lagrange sweep` runs the cases
    pool.done = [&](const sweep::CaseResult& r) {
      in_cases += r.wall_seconds;
      summary.append(r.index,
                     {std::to_string(r.index), sweep::csv_field(r.metrics[0]), "ok",
                      sweep::csv_field(r.metrics[0]), fmt::format("{:.6f}", r.wall_seconds)});
    };
    const auto t2 = Clock::now();
    sweep::run_pool(compiled, inputs, pending, metrics, pool);
    summary.finish();
    const double wall = since(t2);
    const double rate = static_cast<double>(cases) / wall;
    if (workers == 1) rate1 = rate;
    const double overhead =
        (wall * static_cast<double>(workers) - in_cases) / static_cast<double>(cases);
    fmt::print(
        "  {} worker{}: {:.3f} s, {:.1f} cases/s, efficiency {:.0f} %, overhead {:.3f} "
        "ms/case (pool and summary, outside the cases)\n",
        workers, workers == 1 ? " " : "s", wall, rate,
        100.0 * rate / (rate1 * static_cast<double>(workers)), 1e3 * overhead);
  }
  std::filesystem::remove(summary_path);
}

}  // namespace

int main(int argc, char** argv) {
  sweep::keep_freed_memory();  // as `lagrange sweep` does
  const size_t pendulum = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 1000;
  const size_t kite = argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 100;
  study("double_pendulum.yaml", "l2", 0.5, 1.5, pendulum, 10.0);
  if (kite > 0) study("figure_eight.yaml", "W", 6, 10, kite, 10.0);
  return 0;
}
