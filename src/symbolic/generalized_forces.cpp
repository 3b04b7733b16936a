#include "lagrange/error.hpp"
#include "symbolic/mechanical_terms.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

namespace {

const Point& lookup(const Model& model, const std::string& name, const SourceLoc& loc) {
  const Point* p = model.find_point(name);
  if (p == nullptr) throw ModelError(loc, "unknown point '" + name + "'");
  return *p;
}

}  // namespace

// DESIGN.md §4.2: a force F at x(q) gives Q = (∂x/∂q)ᵀF; a damper with rate ḋ of the
// distance d between its points gives Q = −c ḋ ∂d/∂q (Rayleigh D = ½ c ḋ²).
void add_generalized_forces(const Model& model, MechanicalTerms& terms) {
  const size_t n = model.coordinates.size();
  for (size_t i = 0; i < n && i < model.generalized_forces.size(); ++i) {
    if (depends_on_accelerations(model, model.generalized_forces[i]))
      throw ModelError(
          model.coordinates[i].loc,
          "the generalised force on '" + model.coordinates[i].name + "' depends on accelerations");
    terms.Q[i] += model.generalized_forces[i];
  }
  for (const auto& f : model.forces) {
    const Point& x = lookup(model, f.point, f.loc);
    for (const auto& F : f.force)
      if (depends_on_accelerations(model, F))
        throw ModelError(f.loc, "the force at '" + f.point + "' depends on accelerations");
    const std::vector<Vec3> J = point_jacobian(model, x.pos);
    for (size_t i = 0; i < n; ++i) terms.Q[i] += dot(J[i], f.force);
  }
  for (const auto& d : model.dampers) {
    const Point& a = lookup(model, d.a, d.loc);
    const Point& b = lookup(model, d.b, d.loc);
    Vec3 r{b.pos[0] - a.pos[0], b.pos[1] - a.pos[1], b.pos[2] - a.pos[2]};
    const GiNaC::ex dist = GiNaC::sqrt(dot(r, r));
    const GiNaC::ex rate = derivative_without_accelerations(model, dist);
    for (size_t i = 0; i < n; ++i) {
      const GiNaC::ex ddq = dist.diff(model.coordinates[i].q);
      if (!ddq.is_zero()) terms.Q[i] -= d.c * rate * ddq;
    }
  }
}

}  // namespace lagrange::symbolic
