// The extension lagrange._lagrange (docs/python.md): the library the command uses, bound with
// pybind11. python/lagrange/__init__.py re-exports it as the package `lagrange`.

#include <pybind11/pybind11.h>

#include "errors.hpp"
#include "model.hpp"
#include "run.hpp"
#include "stepper.hpp"

PYBIND11_MODULE(_lagrange, m) {
  m.doc() = "Lagrangian modelling and simulation: the lagrange engine from Python";
  lagrange::python::bind_errors(m);
  lagrange::python::bind_run(m);
  lagrange::python::bind_stepper(m);
  lagrange::python::bind_model(m);
}
