#include "symbolic/time_partials.hpp"

namespace lagrange::symbolic {

GiNaC::ex partial_t(const Kinematics& kin, const GiNaC::ex& e) {
  GiNaC::ex d = e.diff(kin.model->t);
  for (const auto& in : kin.model->inputs) {
    if (e.has(in.u)) d += e.diff(in.u) * in.ud;
    if (e.has(in.ud)) d += e.diff(in.ud) * in.udd;
  }
  return d;
}

GiNaC::ex derivative_without_accelerations(const Kinematics& kin, const GiNaC::ex& e) {
  GiNaC::ex d = partial_t(kin, e);
  for (size_t j = 0; j < kin.q.size(); ++j)
    if (e.has(kin.q[j])) d += e.diff(kin.q[j]) * kin.qdot[j];
  return d;
}

Vec3 point_velocity(const Kinematics& kin, const Vec3& x) {
  Vec3 v;
  for (size_t k = 0; k < 3; ++k) v[k] = derivative_without_accelerations(kin, x[k]);
  return v;
}

std::vector<Vec3> point_jacobian(const Kinematics& kin, const Vec3& x) {
  std::vector<Vec3> J(kin.v.size(), Vec3{0, 0, 0});
  for (size_t col = 0; col < J.size(); ++col)
    for (const auto& [j, kjk] : kin.K[col])
      for (size_t k = 0; k < 3; ++k)
        if (x[k].has(kin.q[j])) J[col][k] += x[k].diff(kin.q[j]) * kjk;
  return J;
}

std::vector<GiNaC::ex> velocity_gradient(const Kinematics& kin, const GiNaC::ex& f) {
  std::vector<GiNaC::ex> g(kin.v.size(), 0);
  for (size_t col = 0; col < g.size(); ++col)
    for (const auto& [j, kjk] : kin.K[col])
      if (f.has(kin.q[j])) g[col] += f.diff(kin.q[j]) * kjk;
  return g;
}

GiNaC::ex dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

bool depends_on_rates(const Kinematics& kin, const GiNaC::ex& e) {
  for (size_t k = 0; k < kin.v.size(); ++k)
    if (e.has(kin.v[k]) || e.has(kin.a[k])) return true;
  return false;
}

bool depends_on_state(const Kinematics& kin, const GiNaC::ex& e) {
  for (const auto& q : kin.q)
    if (e.has(q)) return true;
  return depends_on_rates(kin, e);
}

bool depends_on_accelerations(const Kinematics& kin, const GiNaC::ex& e) {
  for (const auto& a : kin.a)
    if (e.has(a)) return true;
  for (const auto& in : kin.model->inputs)
    if (e.has(in.udd)) return true;
  return false;
}

bool depends_on_body_state(const Kinematics& kin, const GiNaC::ex& e) {
  for (size_t j = kin.plain; j < kin.q.size(); ++j)
    if (e.has(kin.q[j])) return true;
  for (size_t k = kin.plain; k < kin.v.size(); ++k)
    if (e.has(kin.v[k]) || e.has(kin.a[k])) return true;
  return false;
}

}  // namespace lagrange::symbolic
