#include "evaluation.hpp"

#include <pybind11/pybind11.h>

#include "cli/prepare.hpp"

namespace py = pybind11;

namespace lagrange::python {

void choose_evaluation(Dynamics& dynamics, const std::string& compile) {
  // Python's SIGINT handler only marks the signal; PyErr_CheckSignals runs it (on the main
  // thread: elsewhere it returns 0), and its KeyboardInterrupt stops the compiler (issue 37
  // item 10).
  bool raised = false;
  const auto interrupted = [&raised] {
    if (!raised) raised = PyErr_CheckSignals() != 0;
    return raised;
  };
  const bool had = cli::choose_evaluation(dynamics, compile, interrupted);
  if (raised) throw py::error_already_set();
  if (had) return;
  const std::string why =
      "machine code: " + dynamics.machine_code_error() + "; the tape interpreter runs instead";
  if (PyErr_WarnEx(PyExc_RuntimeWarning, why.c_str(), 1) != 0) throw py::error_already_set();
}

}  // namespace lagrange::python
