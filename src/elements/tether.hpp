#pragma once
// A tether as the core sees it after lowering (docs/theory.md §4.5): N segments between nodes
// r₀ … r_N, node 0 and N at the attachment points, interior (and a free end's) nodes with
// Cartesian coordinates of their own.

#include <string>
#include <vector>

#include "elements/elements.hpp"

namespace lagrange::elements {

struct Tether {
  std::string name;
  size_t segments = 1;
  bool full = false;  ///< full model: each segment a uniform rod; else lumped node masses
  enum class Drag { None, Simple, Fine } drag = Drag::None;
  GiNaC::ex length;  ///< ℓ: constant, ℓ(t) or a winch's coordinate
  bool variable_length = false;
  GiNaC::ex mass_per_length, diameter = 0, cd = GiNaC::numeric(6, 5), air_density;
  GiNaC::ex damping = 0;  ///< viscous damping per unit length, N·s/m² (on node velocities)
  std::vector<std::string> nodes;  ///< point names of r₀ … r_N
  YAML::Node node;                 ///< the tether's map, for locations
};

/// Drag forces of one tether at its nodes (docs/theory.md §4.5): for each node point, the
/// force the segments' drag puts there, with w the wind (or zero).
std::vector<Vec3> tether_drag(const Model& model, const Tether& tether, const Wind* wind);

}  // namespace lagrange::elements
