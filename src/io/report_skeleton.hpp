#pragma once
// The kinematic skeleton of the report's 3-D view: the joint trees of a model (Model::tree, from
// `links:`, `dh:` or a URDF) as bones from joint to joint, the joint axes, each prismatic joint's
// rail over its travel in the run, and a base where the trees meet the world.

#include <ginac/ginac.h>

#include <nlohmann/json.hpp>
#include <vector>

#include "lagrange/model.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange::io {

/// A model's skeleton: expressions evaluated at every frame and the layout that names them.
struct Skeleton {
  /// Per frame: each node's world position (3 numbers), then each movable joint's world axis (3).
  std::vector<GiNaC::ex> outputs;
  size_t nodes = 0, axes = 0;
  /// `nodes` [{name, kind: base|joint|anchor|rail|com|point}], `bones` and `rails` ([a, b] node
  /// pairs: a bone's a is its parent's end), `axes` [{node, kind: revolute|prismatic, name}].
  nlohmann::json layout;
};

/// The skeleton of `model`'s joint trees (empty without one). Link frames are the links' bodies'
/// own poses, composed through the tree's joints only for massless links; `traj` gives each
/// prismatic joint's travel.
Skeleton skeleton(const Model& model, const Trajectory& traj);

}  // namespace lagrange::io
