#pragma once
// What Dynamics::try_project works on, set up once per model: the sparse solvers of its two
// minimum-norm problems and every buffer a projection fills (docs/theory.md §4.3, "Projecting
// when the drift matters").

#include <vector>

#include "dynamics/minimum_norm.hpp"
#include "dynamics/tangent_jacobian.hpp"
#include "lagrange/compiled_model.hpp"

namespace lagrange::dynamics {

struct ProjectionWorkspace {
  explicit ProjectionWorkspace(const CompiledModel& cm);

  TangentJacobian tangent;  ///< ∂C/∂q on the free bodies' tangent spaces
  MinimumNorm positions;    ///< over tangent's pattern
  MinimumNorm velocities;   ///< over G's pattern
  /// ∂C/∂q and G with the fixed coordinates' columns zeroed; the tangent Jacobian's values.
  std::vector<double> cq, g, reduced;
  std::vector<double> rhs, x, step, dv;          ///< right-hand side and solutions
  std::vector<double> q_start, v_start, q_here;  ///< states to measure and undo changes
  std::vector<double> terms;                     ///< per constraint, for rounding_floor
};

}  // namespace lagrange::dynamics
