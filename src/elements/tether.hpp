#pragma once
// A tether as the core sees it after lowering (docs/theory.md §4.5): N segments between nodes
// r₀ … r_N, node 0 and N at the attachment points, interior (and a free end's) nodes with
// Cartesian coordinates of their own.

#include <optional>
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
  /// Axial elasticity of the segments (docs/theory.md §4.10): stiffness EA in N and damping D in
  /// N·s on the strain rate (tension EA ε + D ε̇, never compressive).
  struct Elasticity {
    GiNaC::ex EA, damping = 0;
  };
  std::optional<Elasticity> elasticity;  ///< unset: rigid segments (length constraints)
  int length_coordinate = -1;            ///< the winch's coordinate ℓ, or −1
  std::vector<std::string> nodes;        ///< point names of r₀ … r_N
  YAML::Node node;                       ///< the tether's map, for locations
};

/// Drag forces of one tether at its nodes (docs/theory.md §4.5): for each node point, the
/// force the segments' drag puts there, with w the wind (or zero).
std::vector<Vec3> tether_drag(const Model& model, const Tether& tether, const Wind* wind);

/// What the elastic segments of a tether put into the model (docs/theory.md §4.10).
struct ElasticSegments {
  std::vector<Vec3> force;         ///< per node: the pull of the segments on either side
  GiNaC::ex length_force = 0;      ///< Q_ℓ on the winch's coordinate (0 without one)
  std::vector<GiNaC::ex> strain;   ///< per segment: ε = |rⱼ − rⱼ₋₁|/ℓ₀ − 1
  std::vector<GiNaC::ex> tension;  ///< per segment: T = EA ε⁺ + g(ε) max(D ε̇, −EA ε⁺), N
  GiNaC::ex energy = 0;            ///< Σ ½ EA ℓ₀ (ε⁺)², J
};

/// The spring–damper forces of an elastic tether's segments, which only pull
/// (docs/theory.md §4.10); the tether must have `elasticity`.
ElasticSegments elastic_segments(const Model& model, const Tether& tether);

}  // namespace lagrange::elements
