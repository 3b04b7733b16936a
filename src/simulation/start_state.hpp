#pragma once
// The start of a run: the initial state checked against C = 0, Ċ = 0 and projected onto them
// when needed (docs/theory.md §4.3). simulate() and the Stepper start with it.

#include <vector>

#include "lagrange/dynamics.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

/// Makes (q, v) consistent at opt.t0 (or, with opt.project_initial false, checks that it is);
/// a note on what moved goes to traj.notes. Throws SimulationError(t0) when it cannot be.
void make_consistent(Dynamics& dyn, const SimulationOptions& opt, std::vector<double>& q,
                     std::vector<double>& v, Trajectory& traj);

}  // namespace lagrange
