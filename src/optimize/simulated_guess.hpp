#pragma once
// A starting point for the collocation from a simulation of the model itself.

#include <vector>

#include "lagrange/dynamics.hpp"

namespace lagrange::collocation {

/// The states x = (q, v) at `times` (ascending, in [0, T]) of a simulation from (q0, v0) with
/// the model inputs `inputs` held at `values` (DOP853, rtol 1e-8, linear interpolation between
/// samples 1/8 of the shortest gap of `times` apart). Empty when the simulation fails before T.
std::vector<std::vector<double>> simulated_states(Dynamics& dyn, const std::vector<size_t>& inputs,
                                                  const std::vector<double>& values,
                                                  const std::vector<double>& q0,
                                                  const std::vector<double>& v0,
                                                  const std::vector<double>& times);

}  // namespace lagrange::collocation
