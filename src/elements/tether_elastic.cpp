#include "elements/tether.hpp"
#include "model/vec3_algebra.hpp"

namespace lagrange::elements {

using model::dot3;
using model::max_of;
using model::min_of;
using model::scale;
using model::sub;

// docs/theory.md §4.10, Elastic tethers. Segment j between rⱼ₋₁ and rⱼ has the unstretched length
// ℓ₀ = ℓ/N (ℓ may be a winch's coordinate or ℓ(t)) and the strain ε = |rⱼ − rⱼ₋₁|/ℓ₀ − 1. Its
// tension is T = EA ε⁺ + g(ε) max(D ε̇, −EA ε⁺) with ε⁺ = max(ε, 0) and the gate
// g = min(1, ε⁺/δ), δ = 10⁻⁶: a slack segment (ε ≤ 0) carries nothing, a taut one
// (ε ≥ δ) is a spring EA/ℓ₀ in parallel with a dashpot D/ℓ₀ whose sum never pushes,
// T = max(0, EA ε + D ε̇). T pulls rⱼ₋₁ towards rⱼ and back; on the reeled-out
// length ℓ it does the virtual work Q_ℓ = (1/N) Σ [T (1 + ε) − ½ EA (ε⁺)²], so that without
// damping the forces derive from U = Σ ½ EA ℓ₀ (ε⁺)².
ElasticSegments elastic_segments(const Model& m, const Tether& t) {
  const size_t n = t.segments;
  const GiNaC::ex N = GiNaC::numeric(static_cast<int>(n));
  const GiNaC::ex l0 = t.length / N;
  const GiNaC::ex EA = t.elasticity->EA, D = t.elasticity->damping;
  const GiNaC::ex delta = GiNaC::numeric(1, 1000000);
  ElasticSegments out;
  out.force.assign(n + 1, Vec3{0, 0, 0});
  GiNaC::ex on_length = 0;
  for (size_t j = 1; j <= n; ++j) {
    const Vec3 d = sub(m.find_point(t.nodes[j])->pos, m.find_point(t.nodes[j - 1])->pos);
    const GiNaC::ex stretched = GiNaC::sqrt(dot3(d, d));
    const GiNaC::ex strain = stretched / l0 - 1;
    const GiNaC::ex taut = max_of(strain, 0);
    GiNaC::ex tension = EA * taut;
    if (!D.is_zero()) {  // g max(D ε̇, −EA ε⁺): its kinks lie off the slack state (T ≡ 0)
      const GiNaC::ex gate = min_of(1, taut / delta);
      tension += gate * max_of(D * m.time_derivative(strain), -tension);
    }
    const Vec3 pull = scale(tension / stretched, d);
    for (size_t k = 0; k < 3; ++k) {
      out.force[j - 1][k] += pull[k];
      out.force[j][k] -= pull[k];
    }
    const GiNaC::ex energy = EA * l0 / 2 * taut * taut;
    on_length += tension * (1 + strain) - EA / 2 * taut * taut;
    out.energy += energy;
    out.strain.push_back(strain);
    out.tension.push_back(tension);
  }
  if (t.length_coordinate >= 0) out.length_force = on_length / N;
  return out;
}

}  // namespace lagrange::elements
