#include "errors.hpp"

#include "cli/commands.hpp"
#include "lagrange/analysis.hpp"
#include "lagrange/error.hpp"

namespace py = pybind11;

namespace lagrange::python {

namespace {

// The exception types, created once at import and kept for the life of the interpreter.
PyObject* model_error_type = nullptr;
PyObject* simulation_error_type = nullptr;
PyObject* analysis_error_type = nullptr;

// Sets `type(message)` with the given attributes as the current Python error.
void set_error(PyObject* type, const std::string& message, const py::dict& attributes) {
  py::object error = py::reinterpret_borrow<py::object>(type)(message);
  for (const auto& [name, value] : attributes) py::setattr(error, name, value);
  PyErr_SetObject(type, error.ptr());
}

}  // namespace

void raise_simulation_error(const std::string& message, double t, py::object run) {
  set_error(simulation_error_type, message, py::dict(py::arg("time") = t, py::arg("run") = run));
  throw py::error_already_set();
}

void bind_errors(py::module_& m) {
  model_error_type = PyErr_NewExceptionWithDoc(
      "lagrange.ModelError",
      "A mistake in a model: the message reads 'file:line:column: error: …'; .file, .line and "
      ".column locate it (0 when unknown), .detail is the message without the location.",
      PyExc_ValueError, nullptr);
  simulation_error_type = PyErr_NewExceptionWithDoc(
      "lagrange.SimulationError",
      "A numerical failure (singular mass matrix, integrator gave up, NaN): .time is where it "
      "happened, .run the trajectory computed up to there (None outside simulate).",
      PyExc_RuntimeError, nullptr);
  m.add_object("ModelError", py::handle(model_error_type));
  analysis_error_type = PyErr_NewExceptionWithDoc(
      "lagrange.AnalysisError",
      "A numerical failure of linearize or trim (a singular Jacobian, Newton stalled); the "
      "message says why and where.",
      PyExc_RuntimeError, nullptr);
  m.add_object("SimulationError", py::handle(simulation_error_type));
  m.add_object("AnalysisError", py::handle(analysis_error_type));

  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const lagrange::ModelError& e) {
      set_error(model_error_type, e.what(),
                py::dict(py::arg("file") = e.loc().file, py::arg("line") = e.loc().line,
                         py::arg("column") = e.loc().column, py::arg("detail") = e.detail()));
    } catch (const lagrange::SimulationError& e) {
      set_error(simulation_error_type, e.what(),
                py::dict(py::arg("time") = e.time(), py::arg("run") = py::none()));
    } catch (const lagrange::AnalysisError& e) {
      PyErr_SetString(analysis_error_type, e.what());
    } catch (const cli::UsageError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
}

}  // namespace lagrange::python
