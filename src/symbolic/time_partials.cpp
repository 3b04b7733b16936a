#include "symbolic/time_partials.hpp"

#include <algorithm>

namespace lagrange::symbolic {

GiNaC::ex partial_t(const Kinematics& kin, const GiNaC::ex& e) {
  GiNaC::ex d = e.diff(kin.model->t);
  for (const auto& in : kin.model->inputs) {
    if (e.has(in.u)) d += e.diff(in.u) * in.ud;
    if (e.has(in.ud)) d += e.diff(in.ud) * in.udd;
  }
  return d;
}

std::vector<std::pair<char, size_t>> state_symbols(const Kinematics& kin, const GiNaC::ex& e) {
  std::vector<std::pair<char, size_t>> found;
  std::vector<GiNaC::ex> stack{e};
  while (!stack.empty()) {
    const GiNaC::ex x = stack.back();
    stack.pop_back();
    if (GiNaC::is_a<GiNaC::symbol>(x)) {
      auto it = kin.role.find(x);
      if (it != kin.role.end()) found.push_back(it->second);
      continue;
    }
    for (size_t i = 0; i < x.nops(); ++i) stack.push_back(x.op(i));
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  return found;
}

std::vector<size_t> coordinates_in(const Kinematics& kin, const GiNaC::ex& e) {
  std::vector<size_t> js;
  for (const auto& [kind, index] : state_symbols(kin, e))
    if (kind == 'q') js.push_back(index);
  return js;
}

std::vector<size_t> velocities_in(const Kinematics& kin, const GiNaC::ex& e) {
  std::vector<size_t> ks;
  for (const auto& [kind, index] : state_symbols(kin, e))
    if (kind == 'v') ks.push_back(index);
  return ks;
}

GiNaC::ex derivative_without_accelerations(const Kinematics& kin, const GiNaC::ex& e) {
  GiNaC::ex d = partial_t(kin, e);
  for (size_t j : coordinates_in(kin, e)) d += e.diff(kin.q[j]) * kin.qdot[j];
  return d;
}

Vec3 point_velocity(const Kinematics& kin, const Vec3& x) {
  Vec3 v;
  for (size_t k = 0; k < 3; ++k) v[k] = derivative_without_accelerations(kin, x[k]);
  return v;
}

std::vector<Vec3> point_jacobian(const Kinematics& kin, const Vec3& x) {
  std::vector<Vec3> J(kin.v.size(), Vec3{0, 0, 0});
  for (size_t k = 0; k < 3; ++k)
    for (size_t j : coordinates_in(kin, x[k])) {
      const GiNaC::ex dx = x[k].diff(kin.q[j]);
      for (const auto& [col, kjk] : kin.K_rows[j]) J[col][k] += dx * kjk;
    }
  return J;
}

std::vector<GiNaC::ex> velocity_gradient(const Kinematics& kin, const GiNaC::ex& f) {
  std::vector<GiNaC::ex> g(kin.v.size(), 0);
  for (size_t j : coordinates_in(kin, f)) {
    const GiNaC::ex df = f.diff(kin.q[j]);
    for (const auto& [col, kjk] : kin.K_rows[j]) g[col] += df * kjk;
  }
  return g;
}

GiNaC::ex dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

bool depends_on_rates(const Kinematics& kin, const GiNaC::ex& e) {
  for (const auto& [kind, index] : state_symbols(kin, e))
    if (kind != 'q') return true;
  return false;
}

bool depends_on_state(const Kinematics& kin, const GiNaC::ex& e) {
  return !state_symbols(kin, e).empty();
}

bool depends_on_accelerations(const Kinematics& kin, const GiNaC::ex& e) {
  for (const auto& [kind, index] : state_symbols(kin, e))
    if (kind == 'a') return true;
  for (const auto& in : kin.model->inputs)
    if (e.has(in.udd)) return true;
  return false;
}

bool depends_on_body_state(const Kinematics& kin, const GiNaC::ex& e) {
  for (const auto& [kind, index] : state_symbols(kin, e))
    if (index >= kin.plain) return true;
  return false;
}

}  // namespace lagrange::symbolic
