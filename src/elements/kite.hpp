#pragma once
// Kites (docs/theory.md §4.7): aerodynamic loads on a point (point-mass kite) or on a free body
// (rigid kite), lowered into point forces and body torques. Sign conventions: v_a = ṙ − w is the
// kite's velocity relative to the air; body axes are the flight-mechanics axes (x forward, y
// right wing, z down); α = atan2(w_b, u_b), β = asin(v_b/|v_a|) (the textbook sideslip).

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "elements/elements.hpp"

namespace lagrange::elements {

/// The inputs of a stability-derivative model, as expressions.
struct AeroInputs {
  GiNaC::ex alpha, beta, phat, qhat, rhat, aileron, elevator, rudder;
};

/// One coefficient C = Σ_x (k₀ + k₁α + k₂α²)·x over x ∈ {1, α, β, p̂, q̂, r̂, δa, δe, δr};
/// each polynomial is a list of decimal strings, read exactly.
struct DerivativeTable {
  std::vector<std::pair<std::string, std::vector<std::string>>> terms;  ///< input → [k₀, k₁, k₂]
  GiNaC::ex evaluate(const AeroInputs& in) const;
};

/// Published data for a kite (`preset:`): mass, inertia, geometry, and either a full
/// stability-derivative model (C_X … C_n) for rigid kites or the point-mass drag polar.
struct KitePreset {
  std::string name, source;
  GiNaC::ex mass, area, span, chord, cd0, aspect_ratio;
  Mat3 inertia;
  std::array<DerivativeTable, 6> coefficients;  ///< C_X, C_Y, C_Z, C_l, C_m, C_n (body axes)
};

/// The preset called `name`, or nullptr; `known` lists the names.
const KitePreset* find_kite_preset(const std::string& name);
std::string kite_preset_names();

/// An exact rational for a decimal literal such as "-0.0293".
GiNaC::ex exact_decimal(const std::string& text);

/// ISA troposphere density ρ(h) = ρ₀ (1 − γh/T₀)^(g/(γR) − 1) with exact rational constants
/// (T₀ = 288.15 K, γ = 6.5e-3 K/m, R = 287.053 J/(kg K), g = 9.81, ρ₀ = 1.225).
GiNaC::ex isa_density(const GiNaC::ex& height);

/// Point-mass lift direction with roll ψ (awebox form): ê_L = cos ψ ê_n − sin ψ ê_0 with
/// ê_0 = (t × u_a)/|t × u_a|, ê_n = û_a × ê_0, u_a = −v_a, t the tether direction.
Vec3 point_mass_lift_direction(const Vec3& v_a, const Vec3& tether, const GiNaC::ex& roll);

/// α, β and the airspeed from the body-axis components (u, v, w) of v_a.
struct FlowAngles {
  GiNaC::ex alpha, beta, airspeed;
};
FlowAngles flow_angles(const Vec3& v_body);

/// Small 3-vector helpers shared by the kite files.
Vec3 cross3(const Vec3& a, const Vec3& b);
GiNaC::ex dot_product(const Vec3& a, const Vec3& b);
Vec3 scaled(const GiNaC::ex& s, const Vec3& a);
Vec3 minus(const Vec3& a, const Vec3& b);
GiNaC::ex length3(const Vec3& a);

void declare_kites(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx);
void lower_kites(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx);

}  // namespace lagrange::elements
