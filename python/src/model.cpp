#include "model.hpp"

#include <pybind11/stl.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "analysis.hpp"
#include "arrays.hpp"
#include "cli/commands.hpp"
#include "errors.hpp"
#include "evaluation.hpp"
#include "interrupt.hpp"
#include "lagrange/io.hpp"
#include "optimize.hpp"
#include "run.hpp"
#include "stepper.hpp"
#include "study.hpp"
#include "support/seconds_since.hpp"

namespace py = pybind11;

namespace lagrange::python {

namespace {

// The file's text, so that a pickled model carries it; nullopt when it cannot be read here (the
// reader then reports why) or when the reader makes the text itself (a bare .urdf file).
std::optional<std::string> file_text(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::path(path).extension() == ".urdf" ||
      !std::filesystem::is_regular_file(path, ec))
    return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || in.bad()) return std::nullopt;
  return text.str();
}

/// Derived equations in the Lagrangian form (as `lagrange derive` prints them), each format made
/// once on first use.
struct PyEquations {
  std::shared_ptr<cli::Prepared> prepared;  // keeps the Model the equations point into alive
  std::shared_ptr<const Equations> equations;
  std::optional<std::string> text, latex, json;

  const std::string& format(std::optional<std::string>& cache, const char* name) {
    if (!cache) cache = format_equations(*equations, name);
    return *cache;
  }
};

// The LaTeX for a notebook: its `% heading` comment lines become plain-text headings between the
// align* blocks that MathJax renders.
std::string notebook_latex(const std::string& latex) {
  std::istringstream in(latex);
  std::string out, line;
  while (std::getline(in, line)) out += (line.rfind("% ", 0) == 0 ? line.substr(2) : line) + "\n";
  return out;
}

const cli::Prepared& prepared(const PyModel& m) {
  return *m.prepared;
}

py::dict parameters(const PyModel& m) {
  const CompiledModel& cm = *m.prepared->compiled;
  const std::vector<double>& values = m.prepared->dynamics->parameters();
  py::dict out;
  for (size_t i = 0; i < cm.np; ++i) out[py::str(cm.parameter_names[i])] = values[i];
  return out;
}

py::object simulate(const PyModel& m, std::optional<double> t_end,
                    std::optional<double> output_step, std::optional<std::string> integrator,
                    std::optional<double> rtol, std::optional<double> atol,
                    std::optional<double> step, const std::string& compile,
                    std::optional<int> max_order) {
  const cli::Prepared& p = prepared(m);
  SimulationOptions so = cli::simulation_options(
      *p.model, cli::RunSettings{t_end, output_step, rtol, atol, step, integrator, max_order});
  so.jacobian_source = cli::jacobian_source(p, so.integrator.method, kLagrangianHint);
  // A workspace of its own, so that runs of one model on several threads never share scratch.
  Dynamics dynamics(p.compiled, p.dynamics->parameters());
  dynamics.set_baumgarte(baumgarte_rate(p.model->stabilization, so.integrator.method));
  choose_evaluation(dynamics, compile);
  auto run = std::make_unique<Run>();
  run->prepared = m.prepared;
  run->integrator = so.integrator.method;
  InterruptibleRun interruptible;
  so.interrupt = interruptible.flag();
  {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    run->trajectory = lagrange::simulate(dynamics, so, p.q, p.v);
    run->wall_seconds = lagrange::seconds_since(start);
  }
  if (!p.initial.was_consistent)
    run->trajectory.notes.insert(run->trajectory.notes.begin(), p.initial.note());
  const Trajectory::Status status = run->trajectory.status;
  const std::string message = run->trajectory.message;
  const double failed_at = run->trajectory.failure_time;
  py::object result = py::cast(std::move(run));
  // Ctrl-C: KeyboardInterrupt carrying the rows so far (.run, status 'interrupted').
  if (interruptible.raised()) InterruptibleRun::throw_with({{"run", result}});
  if (status == Trajectory::Status::Failed) raise_simulation_error(message, failed_at, result);
  return result;
}

// q̇ is not returned: for plain coordinates it is v; a = v̇ (q̈ for plain coordinates).
py::object forward(PyModel& m, const DoubleArray& q_in, const DoubleArray& v_in, double t) {
  cli::Prepared& p = *m.prepared;
  const CompiledModel& cm = *p.compiled;
  const double* q = vector_data(q_in, cm.nq, "q");
  const double* v = vector_data(v_in, cm.nv, "v");
  py::array_t<double> a(static_cast<py::ssize_t>(cm.nv)), lambda(static_cast<py::ssize_t>(cm.m));
  m.qdot.resize(cm.nq);
  p.dynamics->forward(t, q, v, m.qdot.data(), a.mutable_data(), lambda.mutable_data());
  if (cm.m == 0) return std::move(a);
  return py::make_tuple(a, lambda);
}

py::object forward_batch(const PyModel& m, const DoubleArray& Q, const DoubleArray& V, double t) {
  const cli::Prepared& p = prepared(m);
  const CompiledModel& cm = *p.compiled;
  require_matrix(Q, cm.nq, "Q");
  require_matrix(V, cm.nv, "V");
  const size_t rows = static_cast<size_t>(Q.shape(0));
  if (static_cast<size_t>(V.shape(0)) != rows)
    throw py::value_error("V: expected " + std::to_string(rows) + " rows like Q, got " +
                          std::to_string(V.shape(0)));
  py::array_t<double> A({rows, cm.nv}), L({rows, cm.m});
  double* a = A.mutable_data();
  double* lambda = L.mutable_data();
  const double* q = Q.data();
  const double* v = V.data();
  {
    py::gil_scoped_release release;
    Dynamics dynamics(p.compiled, p.dynamics->parameters());
    dynamics.set_baumgarte(p.dynamics->baumgarte());
    std::vector<double> qdot(cm.nq);
    for (size_t r = 0; r < rows; ++r)
      dynamics.forward(t, q + r * cm.nq, v + r * cm.nv, qdot.data(), a + r * cm.nv,
                       lambda + r * cm.m);
  }
  if (cm.m == 0) return std::move(A);
  return py::make_tuple(A, L);
}

// initial= in its order (a dict keeps the caller's), as NAME=VALUE pairs.
std::vector<std::pair<std::string, double>> initial_values(const py::dict& given) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [name, value] : given)
    out.emplace_back(name.cast<std::string>(), value.cast<double>());
  return out;
}

py::tuple pickled(const PyModel& m) {
  py::object text = m.source.text ? py::object(py::str(*m.source.text)) : py::none();
  return py::make_tuple(m.source.path, text, m.overrides, m.dynamics, m.initial);
}

PyModel unpickled(const py::tuple& state) {
  if (state.size() != 5) throw std::runtime_error("lagrange.Model: invalid pickled state");
  cli::ModelSource source{state[0].cast<std::string>(),
                          state[1].cast<std::optional<std::string>>()};
  return load_model(std::move(source), state[2].cast<ParameterOverrides>(),
                    state[3].cast<std::string>(),
                    state[4].cast<std::vector<std::pair<std::string, double>>>());
}

}  // namespace

PyModel load_model(cli::ModelSource source, ParameterOverrides overrides,
                   const std::string& dynamics,
                   std::vector<std::pair<std::string, double>> initial) {
  PyModel m{std::move(source), std::move(overrides), dynamics, std::move(initial), nullptr, {}, {}};
  m.prepared = std::make_shared<cli::Prepared>(
      cli::prepare_source(m.source, m.overrides, dynamics, m.initial));
  return m;
}

void bind_model(py::module_& m) {
  py::class_<PyEquations>(m, "Equations",
                          "Euler–Lagrange equations as `lagrange derive` prints them; Jupyter "
                          "shows them as LaTeX.")
      .def_property_readonly(
          "text", [](PyEquations& e) { return e.format(e.text, "text"); }, "Plain text.")
      .def_property_readonly(
          "latex", [](PyEquations& e) { return e.format(e.latex, "latex"); }, "LaTeX source.")
      .def_property_readonly(
          "json", [](PyEquations& e) { return e.format(e.json, "json"); }, "A JSON document.")
      .def("_repr_latex_",
           [](PyEquations& e) { return notebook_latex(e.format(e.latex, "latex")); })
      .def("__str__", [](PyEquations& e) { return e.format(e.text, "text"); });

  py::class_<PyModel>(m, "Model",
                      "A model read, derived, compiled and checked as `lagrange simulate` does; "
                      "make one with lagrange.load or lagrange.loads.")
      .def_property_readonly(
          "name", [](const PyModel& pm) { return prepared(pm).model->name; }, "The model's name.")
      .def_property_readonly(
          "path", [](const PyModel& pm) { return pm.source.path; },
          "The file it was read from (or the label given to loads).")
      .def_property_readonly(
          "coordinates", [](const PyModel& pm) { return prepared(pm).compiled->coordinate_names; },
          "Position coordinates q, in state order.")
      .def_property_readonly(
          "velocities", [](const PyModel& pm) { return prepared(pm).compiled->velocity_names; },
          "Velocities v, in state order (NAME_dot for plain coordinates).")
      .def_property_readonly(
          "constraints", [](const PyModel& pm) { return prepared(pm).compiled->constraint_names; },
          "Constraint names (one multiplier λ each).")
      .def_property_readonly("parameters", &parameters, "Parameter values by name.")
      .def_property_readonly(
          "inputs", [](const PyModel& pm) { return prepared(pm).compiled->input_names; },
          "Names of the model's inputs (functions of t written in the file).")
      .def_property_readonly(
          "columns", [](const PyModel& pm) { return trajectory_columns(*prepared(pm).compiled); },
          "The columns a run of this model has.")
      .def_property_readonly(
          "initial_state",
          [](const PyModel& pm) {
            return py::make_tuple(to_array(prepared(pm).q), to_array(prepared(pm).v));
          },
          "(q, v) a run starts from: the file's, made consistent with the constraints.")
      .def(
          "derive",
          [](const PyModel& pm) {
            PyEquations e;
            e.prepared = pm.prepared;
            e.equations = std::make_shared<const Equations>(derive(*pm.prepared->model));
            return e;
          },
          "The equations of motion (Lagrangian form, as `lagrange derive`).")
      .def("simulate", &simulate, py::arg("t_end") = py::none(),
           py::arg("output_step") = py::none(), py::arg("integrator") = py::none(),
           py::arg("rtol") = py::none(), py::arg("atol") = py::none(), py::arg("step") = py::none(),
           py::arg("compile") = "auto", py::arg("max_order") = py::none(),
           "Simulate from the initial state (unset settings keep the file's simulate: values; "
           "max_order caps the BDF methods' order, 1 to 5), with the GIL released. Raises "
           "SimulationError carrying the partial run on failure; Ctrl-C raises KeyboardInterrupt "
           "carrying it as .run.")
      .def("forward", &forward, py::arg("q"), py::arg("v"), py::arg("t") = 0.0,
           "Accelerations v̇ at (t, q, v) (q̈ for plain coordinates); for a constrained model "
           "the tuple (v̇, λ).")
      .def("forward_batch", &forward_batch, py::arg("Q"), py::arg("V"), py::arg("t") = 0.0,
           "forward for each row of Q (rows × nq) and V (rows × nv) with the GIL released: "
           "rows × nv accelerations, or (accelerations, rows × m multipliers).")
      .def(
          "linearize",
          [](const PyModel& pm, std::optional<py::object> q, std::optional<py::object> v,
             const std::vector<std::string>& inputs, const std::vector<std::string>& outputs,
             std::optional<double> discrete, double t, const std::map<std::string, double>& values,
             bool at_trim, const std::vector<std::string>& free,
             const std::vector<std::string>& fix, const std::vector<std::string>& steady,
             double tol) {
            return linearize_model(pm, std::move(q), std::move(v), inputs, outputs, discrete, t,
                                   values, TrimFirst{at_trim, free, fix, steady, tol});
          },
          py::arg("q") = py::none(), py::arg("v") = py::none(),
          py::arg("inputs") = std::vector<std::string>{},
          py::arg("outputs") = std::vector<std::string>{}, py::arg("discrete") = py::none(),
          py::arg("t") = 0.0, py::arg("values") = std::map<std::string, double>{},
          py::arg("at_trim") = false, py::arg("free") = std::vector<std::string>{},
          py::arg("fix") = std::vector<std::string>{},
          py::arg("steady") = std::vector<std::string>{}, py::arg("tol") = cli::Options{}.tol,
          "The linear model about (q, v) (default: the initial state) on the constraint "
          "manifold, as `lagrange linearize`: a namespace with A, B, C, D (numpy), states, "
          "inputs (model inputs or parameters), outputs, modes, basis, dt (discrete > 0: "
          "zero-order hold), trim. values={'F': 10.7} sets parameters and model inputs there; "
          "at_trim=True trims first with free, fix, steady and tol as `lagrange trim` (as "
          "`linearize --at-trim`), and trim then says how (iterations, residual, inputs found). "
          "Raises AnalysisError when the KKT matrix is singular.")
      .def("trim", &trim_model, py::arg("q") = py::none(),
           py::arg("free") = std::vector<std::string>{},
           py::arg("fix") = std::vector<std::string>{}, py::arg("tol") = cli::Options{}.tol,
           py::arg("max_iterations") = 100, py::arg("t") = 0.0,
           py::arg("steady") = std::vector<std::string>{}, py::arg("v") = py::none(),
           "An equilibrium (v = 0, a = 0) from q (default: the initial state) by "
           "Levenberg–Marquardt, or pseudo-transient continuation when that fails, as `lagrange "
           "trim`; steady=['phi_dot', …] holds those rates at their values in v (default: the "
           "initial rates), a steady state; free may name parameters or model inputs. A "
           "namespace with q, v, coordinates, iterations, residual, tolerance, not_isolated, "
           "inputs (the free ones' values), drift and pseudo_transient. Raises AnalysisError "
           "saying why when it stalls.")
      .def("jacobian", &jacobian_model, py::arg("q") = py::none(), py::arg("v") = py::none(),
           py::arg("inputs") = std::vector<std::string>{}, py::arg("t") = 0.0,
           "The exact Jacobians at (q, v) (default: the initial state): a namespace with a, "
           "qdot, lam, a_q, a_v, a_w (columns: inputs, model inputs or parameters), qdot_q, "
           "qdot_v, G, C_q, and the implicit form's K = [M Gᵀ; G 0] and Phi_x = ∂Φ/∂(q, v, "
           "inputs) (dense numpy), with ∂(a, λ)/∂x = −K⁻¹ Phi_x.")
      .def(
          "optimize", &optimize_model, py::arg("intervals") = py::none(),
          py::arg("degree") = py::none(), py::arg("ipopt") = std::map<std::string, py::object>{},
          py::arg("verify") = false, py::arg("verbose") = false, py::arg("hessian") = "auto",
          py::arg("compile") = "auto",
          "Solve the file's optimal_control problem as `lagrange optimize` does (intervals and "
          "degree override the file's; ipopt={'key': value} passes options through; verify "
          "re-simulates the controls; compile='auto'|'on'|'off' as simulate's, for the Hessian's "
          "second derivatives), with the GIL released: a namespace with optimal, status, "
          "objective, horizon, controls (intervals × controls), control_names, run (the "
          "collocated trajectory as a Run), violation, worst_constraint, active_bounds, "
          "energy_balance (change, work by source, residual, scale, relative_residual, "
          "unsuitable), "
          "iterations, "
          "setup_seconds, solve_seconds, function_seconds, stages (the homotopy's, each with name, "
          "optimal, status, iterations, objective, tracking, seconds) and verify (final_gap, "
          "largest_gap, message, or None). Ctrl-C raises KeyboardInterrupt carrying that namespace "
          "at "
          "Ipopt's last iterate as .result.")
      .def("stepper", &make_stepper, py::arg("t_end") = py::none(),
           py::arg("integrator") = py::none(), py::arg("rtol") = py::none(),
           py::arg("atol") = py::none(), py::arg("step") = py::none(), py::arg("compile") = "auto",
           py::arg("max_order") = py::none(),
           "A Stepper from the initial state (unset settings keep the file's simulate: values; "
           "t_end is where dop853 lands its last step, as in simulate, and stepping past it is "
           "allowed).")
      .def(
          "export_c",
          [](const PyModel& pm, const std::string& dir) { export_c(*prepared(pm).compiled, dir); },
          py::arg("dir"),
          "Write lagrange_model.h and lagrange_model.c (standalone C99) into dir, as `lagrange "
          "export`.")
      .def(
          "_run_cases",
          [](const PyModel& pm, const std::vector<std::map<std::string, double>>& cases,
             const std::vector<std::string>& metrics, std::optional<double> t_end,
             std::optional<double> output_step, std::optional<std::string> integrator,
             std::optional<double> rtol, std::optional<double> atol, std::optional<double> step,
             std::optional<int> max_order, bool check_only) {
            return run_cases(
                pm, cases, metrics,
                cli::RunSettings{t_end, output_step, rtol, atol, step, integrator, max_order},
                check_only);
          },
          py::arg("cases"), py::arg("metrics"), py::kw_only(), py::arg("t_end") = py::none(),
          py::arg("output_step") = py::none(), py::arg("integrator") = py::none(),
          py::arg("rtol") = py::none(), py::arg("atol") = py::none(), py::arg("step") = py::none(),
          py::arg("max_order") = py::none(), py::arg("check_only") = false,
          "The cases of a study (lagrange.sweep) run here, one dict per case.")
      .def(
          "_optimize_cases",
          [](const PyModel& pm, const std::vector<std::map<std::string, double>>& cases,
             const std::vector<std::string>& metrics, std::optional<int> intervals,
             std::optional<int> degree, const std::map<std::string, py::object>& ipopt,
             const std::string& hessian) {
            if ((intervals && *intervals < 1) || (degree && (*degree < 1 || *degree > 5)))
              throw py::value_error("expected intervals >= 1 and degree from 1 to 5");
            if (hessian != "auto" && hessian != "exact" && hessian != "limited-memory")
              throw py::value_error("expected hessian 'auto', 'exact' or 'limited-memory', got '" +
                                    hessian + "'");
            OptimizeOptions o;
            o.intervals = intervals.value_or(0);
            o.degree = degree.value_or(0);
            o.hessian = hessian == "exact"            ? HessianChoice::Exact
                        : hessian == "limited-memory" ? HessianChoice::LimitedMemory
                                                      : HessianChoice::Auto;
            for (const auto& [key, value] : ipopt)
              o.ipopt.emplace_back(key, py::str(value).cast<std::string>());
            return optimize_cases(pm, cases, metrics, o);
          },
          py::arg("cases"), py::arg("metrics"), py::kw_only(), py::arg("intervals") = py::none(),
          py::arg("degree") = py::none(), py::arg("ipopt") = std::map<std::string, py::object>{},
          py::arg("hessian") = "auto",
          "The cases of an optimisation study (lagrange.sweep(optimize=True)), one dict per case.")
      .def("__repr__",
           [](const PyModel& pm) {
             const CompiledModel& cm = *prepared(pm).compiled;
             return "<lagrange.Model '" + prepared(pm).model->name + "': " + std::to_string(cm.nq) +
                    " coordinates, " + std::to_string(cm.m) + " constraints>";
           })
      .def(py::pickle(&pickled, &unpickled));

  m.def(
      "load",
      [](const std::string& path, const ParameterOverrides& set, const py::dict& initial,
         const std::string& dynamics) {
        return load_model(cli::ModelSource{path, file_text(path)}, set, dynamics,
                          initial_values(initial));
      },
      py::arg("path"), py::kw_only(), py::arg("set") = ParameterOverrides{},
      py::arg("initial") = py::dict(), py::arg("dynamics") = "auto",
      "Read a model file with parameter values `set` replacing the file's and `initial` values of "
      "coordinates and velocities (NAME_dot) replacing its initial state; derive, compile and "
      "check it. `dynamics`: auto, lagrangian or recursive (as `lagrange simulate --dynamics`).");
  m.def(
      "loads",
      [](const std::string& text, const ParameterOverrides& set, const py::dict& initial,
         const std::string& dynamics, const std::string& label) {
        // A label is printed as the file of every error's location: a line end in it could
        // make a message show another file and line (issue 37 item 20).
        if (std::any_of(label.begin(), label.end(),
                        [](unsigned char c) { return c < 0x20 || c == 0x7f; }))
          throw py::value_error("label: expected one line of printable text");
        return load_model(cli::ModelSource{label, text}, set, dynamics, initial_values(initial));
      },
      py::arg("text"), py::kw_only(), py::arg("set") = ParameterOverrides{},
      py::arg("initial") = py::dict(), py::arg("dynamics") = "auto", py::arg("label") = "<string>",
      "As load, for YAML text; `label` names it in error messages.");
}

}  // namespace lagrange::python
