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

// docs/theory.md §4.2: a force F at x(q) gives Q = JᵀF with J = ∂ẋ/∂v; a damper with rate ḋ of
// the distance d between its points gives Q = −c ḋ ∂ḋ/∂v (Rayleigh D = ½ c ḋ²).
void add_generalized_forces(const Kinematics& kin, MechanicalTerms& terms) {
  const Model& model = *kin.model;
  const size_t n = kin.v.size();
  for (size_t i = 0; i < model.coordinates.size() && i < model.generalized_forces.size(); ++i) {
    if (depends_on_accelerations(kin, model.generalized_forces[i]))
      throw ModelError(
          model.coordinates[i].loc,
          "the generalised force on '" + model.coordinates[i].name + "' depends on accelerations");
    terms.Q[i] += model.generalized_forces[i];
  }
  for (const auto& f : model.forces) {
    const Point& x = lookup(model, f.point, f.loc);
    for (const auto& F : f.force)
      if (depends_on_accelerations(kin, F))
        throw ModelError(f.loc, "the force at '" + f.point + "' depends on accelerations");
    const std::vector<Vec3> J = point_jacobian(kin, x.pos);
    for (size_t i = 0; i < n; ++i) terms.Q[i] += dot(J[i], f.force);
  }
  for (const auto& d : model.dampers) {
    const Point& a = lookup(model, d.a, d.loc);
    const Point& b = lookup(model, d.b, d.loc);
    Vec3 r{b.pos[0] - a.pos[0], b.pos[1] - a.pos[1], b.pos[2] - a.pos[2]};
    const GiNaC::ex dist = GiNaC::sqrt(dot(r, r));
    const GiNaC::ex rate = derivative_without_accelerations(kin, dist);
    const std::vector<GiNaC::ex> ddq = velocity_gradient(kin, dist);
    for (size_t i = 0; i < n; ++i)
      if (!ddq[i].is_zero()) terms.Q[i] -= d.c * rate * ddq[i];
  }
}

}  // namespace lagrange::symbolic
