#pragma once
// lagrange.ModelError and lagrange.SimulationError: the library's exceptions as Python exceptions
// with the same messages and their locations as attributes.

#include <pybind11/pybind11.h>

#include <string>

namespace lagrange::python {

/// Creates ModelError (a ValueError with .file, .line, .column, .detail) and SimulationError (a
/// RuntimeError with .time and .run) in `m` and translates lagrange::ModelError,
/// lagrange::SimulationError and the front-end's UsageError (ValueError) into them.
void bind_errors(pybind11::module_& m);

/// Raises lagrange.SimulationError(message) with .time = t and .run = run (a Run or None): sets
/// the Python error and throws pybind11::error_already_set.
[[noreturn]] void raise_simulation_error(const std::string& message, double t,
                                         pybind11::object run);

}  // namespace lagrange::python
