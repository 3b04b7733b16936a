#pragma once
// Model.optimize: the model file's optimal_control problem solved as `lagrange optimize` solves it
// (docs/theory.md §10), with the collocated trajectory as a lagrange.Run.

#include <pybind11/pybind11.h>

#include <map>
#include <optional>
#include <string>

#include "lagrange/optimal_control.hpp"
#include "model.hpp"

namespace lagrange::python {

/// The model's optimal_control problem, or ValueError: the file has none, or the model was loaded
/// in the recursive form (`what` and `command` name the caller and its command-line counterpart).
const OptimalControlSpec& optimal_control_of(const PyModel& m, const std::string& what,
                                             const std::string& command);

/// Solves the problem of the model's `optimal_control:` section (intervals and degree override the
/// file's, ipopt options pass through, verify re-simulates the controls, compile chooses the
/// Hessian's machine code as simulate's does): a
/// types.SimpleNamespace with the status, objective, controls, the Run and Ipopt's statistics.
pybind11::object optimize_model(const PyModel& m, std::optional<int> intervals,
                                std::optional<int> degree,
                                const std::map<std::string, pybind11::object>& ipopt, bool verify,
                                bool verbose, const std::string& hessian,
                                const std::string& compile);

}  // namespace lagrange::python
