#pragma once
// Checks of a model's initial state made before a run writes anything: an inconsistent state
// that cannot be projected onto the constraints, or a singular mass matrix, is a mistake in the
// model (exit 1), reported at its place in the file.

#include <string>
#include <vector>

#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/model.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange::cli {

/// Makes (q, v) consistent with the constraints (docs/theory.md §4.3) in place and returns what
/// was done. Throws ModelError at the first constraint that cannot be met, saying by how much and
/// which `fixed: true` coordinates stand in the way.
InitialConsistency require_consistent_initial_state(const Model& model, Dynamics& dyn,
                                                    std::vector<double>& q, std::vector<double>& v);

/// Forward dynamics at (q, v), t = 0. A singular mass matrix there (a zero mass, a zero-length
/// link) is a ModelError at the coordinate without inertia, naming the parameters it depends on
/// (in the recursive form through require_positive_pivots).
void require_regular_initial_state(const Model& model, const Equations& eq, Dynamics& dyn,
                                   const std::vector<double>& q, const std::vector<double>& v);

/// Recursive equations `eq`: their articulated-body pivots at the state of `dyn`'s last
/// evaluation must all be positive (M positive definite, docs/theory.md §4.9), or a ModelError
/// names the coordinate without inertia and the parameters its pivot depends on.
void require_positive_pivots(const Model& model, const Equations& eq, const Dynamics& dyn);

}  // namespace lagrange::cli
