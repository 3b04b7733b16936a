#pragma once
// A starting point for the collocation from a simulation of the model itself.

#include <optional>
#include <vector>

#include "lagrange/dynamics.hpp"

namespace lagrange::collocation {

/// The states x = (q, v) at `times` and the controls' values there.
struct SimulatedGuess {
  std::vector<std::vector<double>> states, controls;
};

/// A simulation from (q0, v0) over `times` (ascending, in [0, T]; DOP853, rtol 1e-8, linear
/// interpolation between samples 1/8 of the shortest gap of `times` apart). Control c (model input
/// `inputs[c]`) is held at `held[c]` where given, else it follows its declared expression, the
/// model's own schedule (docs/theory.md §10, "Initial guess"). Empty when the simulation fails
/// before T.
SimulatedGuess simulated_states(Dynamics& dyn, const std::vector<size_t>& inputs,
                                const std::vector<std::optional<double>>& held,
                                const std::vector<double>& q0, const std::vector<double>& v0,
                                const std::vector<double>& times);

}  // namespace lagrange::collocation
