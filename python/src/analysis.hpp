#pragma once
// Model.linearize and Model.trim: the library's exact linearisation and trim (docs/theory.md §5)
// on a loaded model, as `lagrange linearize` and `lagrange trim` compute them.

#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "model.hpp"

namespace lagrange::python {

/// A, B, C, D (numpy), names, modes and the basis at (q, v) (default: the model's consistent
/// initial state), as a types.SimpleNamespace; `discrete` > 0 gives the zero-order hold.
pybind11::object linearize_model(const PyModel& m, std::optional<pybind11::object> q,
                                 std::optional<pybind11::object> v,
                                 const std::vector<std::string>& inputs,
                                 const std::vector<std::string>& outputs,
                                 std::optional<double> discrete, double t);

/// An equilibrium from q (default: the initial state) varying the `free` tangent coordinates
/// (all when empty) minus `fix`: q, v = 0, iterations and residual as a types.SimpleNamespace.
pybind11::object trim_model(const PyModel& m, std::optional<pybind11::object> q,
                            const std::vector<std::string>& free,
                            const std::vector<std::string>& fix, double tol, int max_iterations,
                            double t);

}  // namespace lagrange::python
