#include "stepper.hpp"

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <memory>

#include "arrays.hpp"
#include "errors.hpp"
#include "evaluation.hpp"
#include "lagrange/error.hpp"
#include "lagrange/stepper.hpp"
#include "run.hpp"

namespace py = pybind11;

namespace lagrange::python {

namespace {

/// A Stepper with the model it steps (shared with the Model, never changed) and the Python law,
/// if any, that it calls.
struct PyStepper {
  std::shared_ptr<const cli::Prepared> prepared;
  std::unique_ptr<Stepper> stepper;
  std::string integrator;
  py::object law;  // kept alive while the Stepper calls it
};

// The record so far as a Run (a copy: the stepper goes on appending to its own).
std::unique_ptr<Run> record_run(const PyStepper& s) {
  auto run = std::make_unique<Run>();
  run->trajectory = s.stepper->record();
  run->prepared = s.prepared;
  run->integrator = s.integrator;
  return run;
}

// Sets the held values, steps with the GIL released, and turns a failure into
// lagrange.SimulationError carrying the record up to the last good state.
void step(PyStepper& s, double dt, const std::optional<py::dict>& inputs) {
  if (inputs)
    for (const auto& [name, value] : *inputs)
      s.stepper->set_input(name.cast<std::string>(), value.cast<double>());
  std::optional<SimulationError> failure;
  {
    py::gil_scoped_release release;
    try {
      s.stepper->step(dt);
    } catch (const SimulationError& e) {
      failure = e;
    }
  }
  if (failure) raise_simulation_error(failure->what(), failure->time(), py::cast(record_run(s)));
}

// A Python law f(t, q, v) -> values of the external inputs in order, called with the GIL taken
// at every evaluation of the dynamics; None removes it.
void set_law(PyStepper& s, py::object law) {
  if (law.is_none()) {
    s.stepper->set_input_law(nullptr);
    s.law = py::none();
    return;
  }
  if (!PyCallable_Check(law.ptr())) throw py::type_error("law: expected a callable f(t, q, v)");
  const Dynamics& dyn = s.stepper->dynamics();
  const size_t nq = dyn.model().nq, nv = dyn.model().nv;
  const size_t k = s.stepper->external_inputs().size();
  // s.law keeps f alive once set_input_law accepted it: refused during a step ("stepper in
  // use"), the running law must stay referenced.
  PyObject* f = law.ptr();
  s.stepper->set_input_law([f, nq, nv, k](double t, const double* q, const double* v, double* u) {
    py::gil_scoped_acquire gil;
    py::object values = py::reinterpret_borrow<py::object>(f)(
        t, py::array_t<double>(static_cast<py::ssize_t>(nq), q),
        py::array_t<double>(static_cast<py::ssize_t>(nv), v));
    const auto list = values.cast<std::vector<double>>();
    if (list.size() != k)
      throw py::value_error("law: expected " + std::to_string(k) +
                            " values (one per external input), got " + std::to_string(list.size()));
    std::copy(list.begin(), list.end(), u);
  });
  s.law = law;
}

// The model's outputs at t from the last recorded row.
py::dict outputs(const PyStepper& s) {
  const CompiledModel& cm = *s.prepared->compiled;
  const Trajectory& r = s.stepper->record();
  const double* row = r.data.data() + (r.rows() - 1) * r.columns.size();
  const size_t first = 1 + cm.nq + cm.nv + 3;  // after t, q, v, kinetic, potential, energy
  py::dict out;
  for (size_t i = 0; i < cm.output_names.size(); ++i)
    out[py::str(cm.output_names[i])] = row[first + i];
  return out;
}

}  // namespace

py::object make_stepper(const PyModel& m, std::optional<double> t_end,
                        std::optional<std::string> integrator, std::optional<double> rtol,
                        std::optional<double> atol, std::optional<double> step,
                        const std::string& compile, std::optional<int> max_order) {
  const cli::Prepared& p = *m.prepared;
  SimulationOptions so = cli::simulation_options(
      *p.model, cli::RunSettings{t_end, std::nullopt, rtol, atol, step, integrator, max_order});
  so.jacobian_source = cli::jacobian_source(p, so.integrator.method, kLagrangianHint);
  Dynamics dynamics(p.compiled, p.dynamics->parameters());
  dynamics.set_baumgarte(baumgarte_rate(p.model->stabilization, so.integrator.method));
  auto s = std::make_unique<PyStepper>();
  s->prepared = m.prepared;
  s->integrator = so.integrator.method;
  s->stepper = std::make_unique<Stepper>(std::move(dynamics), so, p.q, p.v);
  choose_evaluation(s->stepper->dynamics(), compile);
  return py::cast(std::move(s));
}

void bind_stepper(py::module_& m) {
  py::class_<PyStepper>(
      m, "Stepper",
      "A controller in the loop: advances the model to t + dt with input values set between "
      "calls, keeping the integrator's state (make one with Model.stepper).")
      .def_property_readonly(
          "t", [](const PyStepper& s) { return s.stepper->time(); }, "The time of the state.")
      .def_property_readonly(
          "state",
          [](const PyStepper& s) {
            const std::vector<double>& y = s.stepper->state();
            const size_t nq = s.prepared->compiled->nq;
            return py::make_tuple(to_array({y.begin(), y.begin() + static_cast<long>(nq)}),
                                  to_array({y.begin() + static_cast<long>(nq), y.end()}));
          },
          "(q, v) at t, new arrays.")
      .def_property_readonly("outputs", &outputs, "The model's outputs at t by name.")
      .def_property_readonly(
          "inputs", [](const PyStepper& s) { return s.stepper->external_inputs(); },
          "Names of the inputs step() may set (declared external in the model).")
      .def("step", &step, py::arg("dt"), py::arg("inputs") = py::none(),
           "Hold the given external inputs ({name: value}) from t on, then advance to t + dt "
           "with the GIL released. Raises SimulationError (with .time and .run, the record up "
           "to t) when the integration fails; t and state are then unchanged.")
      .def("set_law", &set_law, py::arg("law"),
           "Evaluate f(t, q, v) -> values of the external inputs (in the order of `inputs`) at "
           "every evaluation of the dynamics instead of held values (None: held values again).")
      .def(
          "trajectory", [](const PyStepper& s) { return record_run(s); },
          "The states so far (t0 and each step's end) as a Run, with the model's columns.")
      .def("__repr__", [](const PyStepper& s) {
        return "<lagrange.Stepper '" + s.prepared->model->name +
               "' at t = " + std::to_string(s.stepper->time()) + ", " + s.integrator + ">";
      });
}

}  // namespace lagrange::python
