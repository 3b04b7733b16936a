#pragma once
// lagrange.Stepper: a controller written in Python in the loop (include/lagrange/stepper.hpp).

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "model.hpp"

namespace lagrange::python {

/// Model.stepper: a Stepper from the model's initial state with the file's simulate: settings,
/// those given replacing them (as Model.simulate).
pybind11::object make_stepper(const PyModel& m, std::optional<double> t_end,
                              std::optional<std::string> integrator, std::optional<double> rtol,
                              std::optional<double> atol, std::optional<double> step,
                              const std::string& compile, std::optional<int> max_order);

/// Binds lagrange.Stepper.
void bind_stepper(pybind11::module_& m);

}  // namespace lagrange::python
