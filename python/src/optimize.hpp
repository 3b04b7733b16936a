#pragma once
// Model.optimize: the model file's optimal_control problem solved as `lagrange optimize` solves it
// (docs/theory.md §10), with the collocated trajectory as a lagrange.Run.

#include <pybind11/pybind11.h>

#include <map>
#include <optional>
#include <string>

#include "model.hpp"

namespace lagrange::python {

/// Solves the problem of the model's `optimal_control:` section (intervals and degree override the
/// file's, ipopt options pass through, verify re-simulates the controls): a
/// types.SimpleNamespace with the status, objective, controls, the Run and Ipopt's statistics.
pybind11::object optimize_model(const PyModel& m, std::optional<int> intervals,
                                std::optional<int> degree,
                                const std::map<std::string, pybind11::object>& ipopt, bool verify,
                                bool verbose, const std::string& hessian);

}  // namespace lagrange::python
