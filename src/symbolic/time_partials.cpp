#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

GiNaC::ex partial_t(const Model& model, const GiNaC::ex& e) {
  GiNaC::ex d = e.diff(model.t);
  for (const auto& in : model.inputs) {
    if (e.has(in.u)) d += e.diff(in.u) * in.ud;
    if (e.has(in.ud)) d += e.diff(in.ud) * in.udd;
  }
  return d;
}

GiNaC::ex derivative_without_accelerations(const Model& model, const GiNaC::ex& e) {
  GiNaC::ex d = partial_t(model, e);
  for (const auto& c : model.coordinates)
    if (e.has(c.q)) d += e.diff(c.q) * c.v;
  return d;
}

Vec3 point_velocity(const Model& model, const Vec3& x) {
  Vec3 v;
  for (size_t k = 0; k < 3; ++k) v[k] = derivative_without_accelerations(model, x[k]);
  return v;
}

GiNaC::ex dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

bool depends_on_rates(const Model& model, const GiNaC::ex& e) {
  for (const auto& c : model.coordinates)
    if (e.has(c.v) || e.has(c.a)) return true;
  return false;
}

bool depends_on_state(const Model& model, const GiNaC::ex& e) {
  for (const auto& c : model.coordinates)
    if (e.has(c.q)) return true;
  return depends_on_rates(model, e);
}

bool depends_on_accelerations(const Model& model, const GiNaC::ex& e) {
  for (const auto& c : model.coordinates)
    if (e.has(c.a)) return true;
  for (const auto& in : model.inputs)
    if (e.has(in.udd)) return true;
  return false;
}

}  // namespace lagrange::symbolic
