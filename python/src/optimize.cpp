#include "optimize.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <stdexcept>

#include "cli/commands.hpp"
#include "interrupt.hpp"
#include "lagrange/error.hpp"
#include "lagrange/optimize.hpp"
#include "run.hpp"

namespace py = pybind11;

namespace lagrange::python {

// docs/theory.md §10 through the library: the CLI's `optimize` and this share optimize() and
const OptimalControlSpec& optimal_control_of(const PyModel& m, const std::string& what,
                                             const std::string& command) {
  const cli::Prepared& p = *m.prepared;
  if (!p.model->optimal_control)
    throw py::value_error(p.model->name +
                          " has no optimal_control section (docs/model-language.md, \"Optimal "
                          "control\")");
  if (p.equations.recursive)
    throw py::value_error(what +
                          " needs the Lagrangian form of the model: load it with "
                          "dynamics='lagrangian' (as `" +
                          command + "` derives it)");
  return *p.model->optimal_control;
}

// verify(), on a workspace of this call's own.
py::object optimize_model(const PyModel& m, std::optional<int> intervals, std::optional<int> degree,
                          const std::map<std::string, py::object>& ipopt, bool verify_result,
                          bool verbose, const std::string& hessian, const std::string& compile) {
  const cli::Prepared& p = *m.prepared;
  optimal_control_of(m, "optimize", "lagrange optimize");
  if ((intervals && *intervals < 1) || (degree && (*degree < 1 || *degree > 5)))
    throw py::value_error("expected intervals >= 1 and degree from 1 to 5");
  const OptimalControlSpec& spec = *p.model->optimal_control;
  OptimizeOptions o;
  o.intervals = intervals.value_or(0);
  o.degree = degree.value_or(0);
  o.verbose = verbose;
  if (hessian != "auto" && hessian != "exact" && hessian != "limited-memory")
    throw py::value_error("expected hessian 'auto', 'exact' or 'limited-memory', got '" + hessian +
                          "'");
  o.hessian = hessian == "exact"            ? HessianChoice::Exact
              : hessian == "limited-memory" ? HessianChoice::LimitedMemory
                                            : HessianChoice::Auto;
  for (const auto& [key, value] : ipopt)
    o.ipopt.emplace_back(key, py::str(value).cast<std::string>());
  o.evaluation = cli::evaluation_mode(compile);
  const SimulationOptions so = cli::simulation_options(*p.model, cli::RunSettings{});
  Dynamics dynamics(p.compiled, p.dynamics->parameters());
  dynamics.set_baumgarte(baumgarte_rate(p.model->stabilization, so.integrator.method));
  OptimizeResult r;
  VerifyResult v;
  InterruptibleRun interruptible;
  o.interrupt = interruptible.flag();
  {
    py::gil_scoped_release release;
    try {
      r = optimize(p.equations, p.compiled, dynamics, spec, p.q, p.v, o);
    } catch (const std::invalid_argument& e) {
      throw ModelError(spec.loc, e.what());
    }
    if (verify_result && r.trajectory.status != Trajectory::Status::Interrupted) {
      SimulationOptions tight = so;
      tight.interrupt = o.interrupt;
      tight.integrator.rtol = 1e-10;
      tight.integrator.atol = 1e-12;
      v = verify(dynamics, spec, r, tight);
    }
  }
  for (const std::string& w : r.warnings)
    if (PyErr_WarnEx(PyExc_UserWarning, w.c_str(), 1) != 0) throw py::error_already_set();
  const size_t nu = r.control_names.size();
  py::array_t<double> controls(
      {static_cast<py::ssize_t>(r.intervals), static_cast<py::ssize_t>(nu)});
  std::copy(r.controls.begin(), r.controls.end(), controls.mutable_data());
  py::array_t<double> control_points({static_cast<py::ssize_t>(r.intervals),
                                      static_cast<py::ssize_t>(r.degree),
                                      static_cast<py::ssize_t>(nu)});
  std::copy(r.control_points.begin(), r.control_points.end(), control_points.mutable_data());
  const std::vector<bool> polynomial = r.polynomial;
  auto run = std::make_unique<Run>();
  run->prepared = m.prepared;
  run->integrator = "Radau IIA collocation";
  run->wall_seconds = r.setup_seconds + r.solve_seconds;
  run->trajectory = std::move(r.trajectory);
  const py::object types = py::module_::import("types");
  py::object verified = py::none();
  if (verify_result)
    verified = types.attr("SimpleNamespace")(py::arg("final_gap") = v.final_gap,
                                             py::arg("largest_gap") = v.largest_gap,
                                             py::arg("message") = v.message);
  py::dict fields;
  fields["optimal"] = r.optimal;
  fields["status"] = r.status;
  fields["objective"] = r.objective;
  fields["horizon"] = r.horizon;
  fields["intervals"] = r.intervals;
  fields["degree"] = r.degree;
  fields["iterations"] = r.iterations;
  fields["exact_hessian"] = r.exact_hessian;
  fields["hessian_note"] = r.hessian_note;
  fields["hessian_evaluation"] = r.hessian_evaluation;
  fields["residual_evaluation"] = r.residual_evaluation;
  fields["violation"] = r.violation;
  fields["worst_constraint"] = r.worst_constraint;
  fields["active_bounds"] = r.active_bounds;
  py::dict work;
  for (const auto& [name, w] : r.energy_balance.work) work[py::str(name)] = w;
  fields["energy_balance"] = types.attr("SimpleNamespace")(
      py::arg("unsuitable") = r.energy_balance.unsuitable,
      py::arg("change") = r.energy_balance.change, py::arg("work") = work,
      py::arg("residual") = r.energy_balance.residual, py::arg("scale") = r.energy_balance.scale,
      py::arg("relative_residual") = r.energy_balance.relative_residual());
  fields["control_names"] = r.control_names;
  fields["controls"] = controls;
  fields["control_points"] = control_points;
  fields["polynomial"] = polynomial;
  fields["run"] = py::cast(std::move(run));
  fields["setup_seconds"] = p.derive_seconds + p.compile_seconds + r.setup_seconds;
  fields["solve_seconds"] = r.solve_seconds;
  fields["function_seconds"] = r.function_seconds;
  fields["verify"] = verified;
  py::list stages;
  for (const StageResult& stage : r.stages)
    stages.append(types.attr("SimpleNamespace")(
        py::arg("name") = stage.name, py::arg("optimal") = stage.optimal,
        py::arg("status") = stage.status, py::arg("iterations") = stage.iterations,
        py::arg("objective") = stage.objective, py::arg("tracking") = stage.tracking,
        py::arg("seconds") = stage.seconds));
  fields["stages"] = stages;
  py::object result = types.attr("SimpleNamespace")(**fields);
  // Ctrl-C: KeyboardInterrupt carrying the result at Ipopt's last iterate (.result).
  if (interruptible.raised()) InterruptibleRun::throw_with({{"result", result}});
  return result;
}

}  // namespace lagrange::python
