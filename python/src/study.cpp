#include "study.hpp"

#include <pybind11/stl.h>

#include <cmath>

#include "cli/commands.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/error.hpp"
#include "lagrange/sweep.hpp"

namespace py = pybind11;

namespace lagrange::python {

py::list run_cases(const PyModel& m, const std::vector<std::map<std::string, double>>& cases,
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
  if (check_only) return py::list();
  // Each case's model read with its values (GiNaC: with the GIL held), then the runs without.
  std::vector<sweep::CaseInput> inputs(cases.size());
  std::vector<std::string> rejected(cases.size());
  std::vector<size_t> runnable;
  for (size_t i = 0; i < cases.size(); ++i) {
    ParameterOverrides values = m.overrides;
    for (const auto& [name, value] : cases[i]) values[name] = value;
    try {
      const Model cm = m.source.read(values);
      SimulationOptions so = cli::simulation_options(cm, settings);
      so.jacobian_source = cli::jacobian_source(p, so.integrator.method, kLagrangianHint);
      inputs[i] = sweep::case_input(cm, *p.compiled, so);
      runnable.push_back(i);
    } catch (const ModelError& e) {
      rejected[i] =
          "the model does not accept these values: " + e.detail() + " (at " + e.loc().str() + ")";
    } catch (const cli::UsageError& e) {
      rejected[i] = e.what();
    } catch (const sweep::StudyError& e) {
      throw py::value_error(e.what());
    }
  }
  std::vector<sweep::CaseResult> results(cases.size());
  {
    py::gil_scoped_release release;
    sweep::PoolOptions pool;
    pool.done = [&](const sweep::CaseResult& r) { results[r.index] = r; };
    // One library for every case (docs/theory.md §9.3): compiled by the first call in a
    // process, loaded from the cache by the next; the interpreter where it cannot be had.
    pool.evaluation = Evaluation::SharedMachineCode;
    sweep::run_pool(p.compiled, inputs, runnable, metrics, pool);
  }
  py::list rows;
  for (size_t i = 0; i < cases.size(); ++i) {
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
  }
  return rows;
}

}  // namespace lagrange::python
