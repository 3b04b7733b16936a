#include "study.hpp"

#include <fmt/format.h>
#include <pybind11/stl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "cli/commands.hpp"
#include "cli/optimal_sweep.hpp"
#include "cli/sweep_inputs.hpp"
#include "interrupt.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/error.hpp"
#include "lagrange/sweep.hpp"
#include "optimize.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace lagrange::python {

namespace {

// What a kept replay depends on besides the model: the varied names and the settings.
std::string replay_key(const cli::CaseValues& names, const cli::RunSettings& s) {
  std::string key;
  for (const auto& [name, value] : names) key += name + '\n';
  const auto add = [&](const auto& v) {
    key += v ? fmt::format("{}", *v) : std::string("-");
    key += '\n';
  };
  add(s.t_end), add(s.output_step), add(s.rtol), add(s.atol), add(s.step), add(s.integrator);
  add(s.max_order);
  return key;
}

}  // namespace

py::tuple run_cases(const PyModel& m, const std::vector<std::map<std::string, double>>& cases,
                    const std::vector<std::string>& metric_specs, const cli::RunSettings& settings,
                    bool check_only) {
  const cli::Prepared& p = *m.prepared;
  if (!m.initial.empty())
    throw py::value_error(
        "sweep: this model was loaded with initial= values; a study reads each case's initial "
        "state from the model file, so load it without initial= (or write them in the file)");
  std::vector<sweep::Metric> metrics;
  try {
    metrics = sweep::study_metrics(*p.model, *p.compiled, metric_specs);
  } catch (const sweep::StudyError& e) {
    throw py::value_error(e.what());
  }
  for (const auto& c : cases)
    for (const auto& [name, value] : c)
      if (p.model->parameter_index(name) < 0)
        throw py::value_error("sweep: no parameter '" + name + "' in " + m.source.path);
  // Settings refused here (ValueError), not as a failed row per case (issue 37 item 6).
  (void)cli::simulation_options(*p.model, settings);
  if (check_only) return py::make_tuple(py::list(), 0);
  // The cases' inputs as `lagrange sweep` has them (cli/sweep_inputs.hpp): replayed from one
  // traced read kept with the model for these parameters and settings, else each case's own
  // read (GiNaC: with the GIL held); the runs then without it.
  std::vector<cli::CaseValues> values;
  for (const auto& c : cases) values.emplace_back(c.begin(), c.end());
  const cli::CaseInputSource from{m.source, m.overrides, [&p, settings](const Model& cm) {
                                    SimulationOptions so = cli::simulation_options(cm, settings);
                                    so.jacobian_source = cli::jacobian_source(
                                        p, so.integrator.method, kLagrangianHint);
                                    return sweep::case_input(cm, *p.compiled, so);
                                  }};
  size_t reads = 0;
  std::shared_ptr<const cli::StudyReplay> replay;
  if (std::all_of(values.begin(), values.end(), [&](const cli::CaseValues& v) {
        return v.size() == values[0].size() &&
               std::equal(v.begin(), v.end(), values[0].begin(),
                          [](const auto& a, const auto& b) { return a.first == b.first; });
      })) {
    std::shared_ptr<const cli::StudyReplay>& kept = m.replays[replay_key(values[0], settings)];
    if (!kept) {
      kept = std::make_shared<const cli::StudyReplay>(cli::replay_study(from, values));
      reads += kept->reads;
      if (!kept->warning.empty()) PyErr_WarnEx(PyExc_RuntimeWarning, kept->warning.c_str(), 1);
    }
    replay = kept;
  }
  std::vector<sweep::CaseInput> inputs(cases.size());
  std::vector<std::string> rejected(cases.size());
  std::vector<size_t> runnable;
  for (size_t i = 0; i < cases.size(); ++i) {
    std::optional<sweep::CaseInput> input;
    if (replay && replay->inputs) input = (*replay->inputs)(values[i]);
    if (!input) {
      ++reads;
      sweep::CaseRead read = cli::read_case_inputs(from, values[i]);
      input = std::move(read.input);
      rejected[i] = std::move(read.rejected);
    }
    if (input) {
      inputs[i] = std::move(*input);
      runnable.push_back(i);
    }
  }
  std::vector<sweep::CaseResult> results(cases.size());
  std::vector<bool> finished(cases.size(), false);  // a case stopped by Ctrl-C has no row
  for (size_t i = 0; i < cases.size(); ++i) finished[i] = !rejected[i].empty();
  InterruptibleRun interruptible;
  {
    py::gil_scoped_release release;
    sweep::PoolOptions pool;
    pool.interrupt = interruptible.flag();
    pool.done = [&](const sweep::CaseResult& r) {
      results[r.index] = r;
      finished[r.index] = true;
    };
    // One library for every case (docs/theory.md §9.3): compiled by the first call in a
    // process, loaded from the cache by the next; the interpreter where it cannot be had.
    pool.evaluation = Evaluation::SharedMachineCode;
    sweep::run_pool(p.compiled, inputs, runnable, metrics, pool);
  }
  py::list rows, indices;
  for (size_t i = 0; i < cases.size(); ++i) {
    if (!finished[i]) continue;
    sweep::CaseResult& r = results[i];
    if (!rejected[i].empty()) {
      r.status = Trajectory::Status::Failed;
      r.reason = rejected[i];
      r.metrics.assign(metrics.size(), std::nan(""));
    }
    py::dict row;
    for (const auto& [name, value] : cases[i]) row[py::str(name)] = value;
    row["status"] = r.status == Trajectory::Status::Complete ? "ok" : "failed";
    row["reason"] = r.reason;
    row["failure_time"] = r.status == Trajectory::Status::Complete ? std::nan("") : r.failure_time;
    for (size_t k = 0; k < metrics.size(); ++k) row[py::str(metrics[k].name)] = r.metrics[k];
    row["wall_s"] = r.wall_seconds;
    rows.append(row);
    indices.append(i);
  }
  // Ctrl-C: KeyboardInterrupt carrying the finished cases' rows, their case numbers and the
  // model reads (.rows, .cases, .reads).
  if (interruptible.raised())
    InterruptibleRun::throw_with({{"rows", rows}, {"cases", indices}, {"reads", py::int_(reads)}});
  return py::make_tuple(rows, reads);
}

py::list optimize_cases(const PyModel& m, const std::vector<std::map<std::string, double>>& cases,
                        const std::vector<std::string>& metric_specs,
                        const OptimizeOptions& options) {
  const cli::Prepared& p = *m.prepared;
  optimal_control_of(m, "sweep(optimize=True)", "lagrange sweep --optimize");
  if (!m.initial.empty())
    throw py::value_error(
        "sweep: this model was loaded with initial= values; a study reads each case's initial "
        "state from the model file, so load it without initial= (or write them in the file)");
  std::vector<sweep::Case> study;
  for (const auto& c : cases) {
    sweep::Case one{study.size(), {c.begin(), c.end()}};
    if (!study.empty() &&
        (one.values.size() != study[0].values.size() ||
         !std::equal(one.values.begin(), one.values.end(), study[0].values.begin(),
                     [](const auto& a, const auto& b) { return a.first == b.first; })))
      throw py::value_error("sweep(optimize=True): every case must give the same parameters");
    for (const auto& [name, value] : one.values)
      if (p.model->parameter_index(name) < 0)
        throw py::value_error("sweep: no parameter '" + name + "' in " + m.source.path);
    study.push_back(std::move(one));
  }
  cli::OptimalStudy os;
  os.prepared = &p;
  os.options = options;
  try {
    os.metrics = sweep::study_metrics(*p.model, *p.compiled, metric_specs,
                                      cli::optimal_trajectory_columns(p));
  } catch (const sweep::StudyError& e) {
    throw py::value_error(e.what());
  }
  py::list rows;
  if (study.empty()) return rows;
  const cli::CaseInputSource from{
      m.source, m.overrides, [&p](const Model& cm) {
        return sweep::case_input(cm, *p.compiled, cli::simulation_options(cm, cli::RunSettings{}));
      }};
  std::vector<double> origin;
  for (const auto& [name, value] : study[0].values)
    origin.push_back(
        p.model->parameters.at(static_cast<size_t>(p.model->parameter_index(name))).value);
  std::vector<size_t> all(study.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  const std::vector<size_t> order = cli::warm_start_order(study, all, origin);
  const fs::path scratch =
      fs::temp_directory_path() / fmt::format("lagrange-warm-start-{}-{}.csv", getpid(),
                                              reinterpret_cast<std::uintptr_t>(&study));
  os.guess_path = scratch.string();
  // Each case's inputs from its own read of the model file (GiNaC: with the GIL held, as the
  // whole study is: a case's solve is seconds, its read milliseconds).
  std::vector<cli::OptimalCaseResult> results(study.size());
  std::map<size_t, Trajectory> solved;
  Dynamics dyn(p.compiled, p.dynamics->parameters());
  cli::run_optimal_cases(
      os, dyn, study, order, [&](size_t i) { return cli::read_case_inputs(from, study[i].values); },
      solved, [&](const cli::OptimalCaseResult& r, const Trajectory&) { results[r.index] = r; });
  for (const fs::path& f : {scratch, fs::path(scratch.string() + ".json")}) {
    std::error_code ec;
    fs::remove(f, ec);
  }
  for (size_t i = 0; i < study.size(); ++i) {
    const cli::OptimalCaseResult& r = results[i];
    py::dict row;
    for (const auto& [name, value] : cases[i]) row[py::str(name)] = value;
    row["status"] = r.optimal ? "ok" : "failed";
    row["reason"] = cli::reason_text(r);
    row["objective"] = r.objective;
    row["horizon"] = r.horizon;
    row["iterations"] = r.iterations;
    row["violation"] = r.violation;
    row["warm_start"] = r.started_from ? py::object(py::int_(*r.started_from)) : py::none();
    for (size_t k = 0; k < os.metrics.size(); ++k) row[py::str(os.metrics[k].name)] = r.metrics[k];
    row["solve_s"] = r.solve_seconds;
    row["wall_s"] = r.wall_seconds;
    rows.append(row);
  }
  return rows;
}

}  // namespace lagrange::python
