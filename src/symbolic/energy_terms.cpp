#include "lagrange/error.hpp"
#include "symbolic/mechanical_terms.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

namespace {

// U = ½ k (|b − a| − l0)² for each spring.
GiNaC::ex spring_potential(const Model& model) {
  GiNaC::ex U = 0;
  for (const auto& s : model.springs) {
    const Point* a = model.find_point(s.a);
    const Point* b = model.find_point(s.b);
    if (a == nullptr || b == nullptr)
      throw ModelError(s.loc, "unknown point '" + (a == nullptr ? s.a : s.b) + "' in spring");
    Vec3 d{b->pos[0] - a->pos[0], b->pos[1] - a->pos[1], b->pos[2] - a->pos[2]};
    GiNaC::ex stretch = GiNaC::sqrt(dot(d, d)) - s.l0;
    U += s.k / 2 * stretch * stretch;
  }
  return U;
}

}  // namespace

// docs/theory.md §4.1: M = ∂²L/∂v∂vᵀ, h = ∂L/∂q − (∂²L/∂v∂qᵀ) v − ∂ₜ(∂L/∂v) over the plain
// coordinates; for free-body coordinates h −= Kᵀ ∂U/∂q (§4.4, the 2P(∂U/∂R) rows).
void add_energy_terms(const Kinematics& kin, MechanicalTerms& terms) {
  const Model& model = *kin.model;
  const size_t n = model.coordinates.size();
  if (depends_on_accelerations(kin, model.kinetic))
    throw ModelError({model.file, 0, 0}, "the kinetic energy depends on accelerations");
  if (depends_on_accelerations(kin, model.potential))
    throw ModelError({model.file, 0, 0}, "the potential energy depends on accelerations");
  if (depends_on_body_state(kin, model.kinetic))
    throw ModelError({model.file, 0, 0},
                     "the kinetic energy depends on a free body's coordinates or velocities; "
                     "expected plain coordinates only (a body's kinetic energy comes from its "
                     "mass and inertia)");
  const GiNaC::ex U = model.potential + spring_potential(model);
  for (size_t k = kin.plain; k < kin.v.size(); ++k)
    if (U.has(kin.v[k]))
      throw ModelError({model.file, 0, 0}, "the potential energy depends on the velocity '" +
                                               kin.v_names[k] + "'; expected U(q, t)");
  const GiNaC::ex L = model.kinetic - U;
  terms.T += model.kinetic;
  terms.U += U;
  if (kin.q.size() > kin.plain) {
    const std::vector<GiNaC::ex> f = velocity_gradient(kin, U);  // Kᵀ ∂U/∂q
    for (size_t k = kin.plain; k < kin.v.size(); ++k) terms.h[k] -= f[k];
  }
  // Only the coordinates and velocities that L and each momentum actually contain are visited.
  for (const auto& [kind, i] : state_symbols(kin, L)) {
    if (i >= n) continue;  // free-body symbols: handled above
    const auto& ci = model.coordinates[i];
    if (kind == 'q') terms.h[i] += L.diff(ci.q);
    if (kind != 'v') continue;
    const GiNaC::ex p = L.diff(ci.v);  // generalised momentum of coordinate i
    for (const auto& [kind_j, j] : state_symbols(kin, p)) {
      if (j >= n) continue;
      const auto& cj = model.coordinates[j];
      if (kind_j == 'v') terms.M(i, j) += p.diff(cj.v);
      if (kind_j == 'q') terms.h[i] -= p.diff(cj.q) * cj.v;
    }
    terms.h[i] -= partial_t(kin, p);
  }
}

}  // namespace lagrange::symbolic
