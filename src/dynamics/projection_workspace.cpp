#include "dynamics/projection_workspace.hpp"

#include <algorithm>

namespace lagrange::dynamics {

ProjectionWorkspace::ProjectionWorkspace(const CompiledModel& cm)
    : tangent(cm.Cq_pattern, cm.nq, cm.rotations),
      positions(tangent.columns(), cm.m, tangent.pattern()),
      velocities(cm.nv, cm.m, cm.G_pattern),
      cq(cm.Cq_pattern.size()),
      g(cm.G_pattern.size()),
      reduced(tangent.pattern().size()),
      rhs(cm.m),
      x(std::max(tangent.columns(), cm.nv)),
      step(cm.nq),
      dv(cm.nv),
      q_start(cm.nq),
      v_start(cm.nv),
      q_here(cm.nq),
      terms(cm.m) {}

}  // namespace lagrange::dynamics
