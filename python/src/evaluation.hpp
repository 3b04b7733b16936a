#pragma once
// compile= of Model.simulate and Model.stepper: machine code or the interpreter, as the command
// line's --compile chooses (cli::choose_evaluation), with Ctrl-C honoured while "on" compiles.

#include <string>

#include "lagrange/dynamics.hpp"

namespace lagrange::python {

/// Evaluation of `dynamics` per `compile` ("auto", "on", "off"). A RuntimeWarning when machine
/// code cannot be had; SIGINT while "on" compiles stops the compiler and raises KeyboardInterrupt
/// (pybind11::error_already_set), as Python's handler decides. Call with the GIL held.
void choose_evaluation(Dynamics& dynamics, const std::string& compile);

}  // namespace lagrange::python
