// docs/theory.md §10, "Checks": the energy balance dH/dt = Q·v of the equations of motion,
// source by source.
#include <algorithm>
#include <cmath>
#include <map>

#include "lagrange/energy_balance.hpp"
#include "model/vec3_algebra.hpp"
#include "symbolic/mechanical_terms.hpp"
#include "symbolic/memo_diff.hpp"
#include "symbolic/time_partials.hpp"

namespace lagrange {

namespace {

std::string at_line(const SourceLoc& loc) {
  return loc.line > 0 ? " (line " + std::to_string(loc.line) + ")" : "";
}

/// Q_s·v for the generalised force of a world force F at x: Σ_k (∂ẋ/∂v_k · F) v_k (§4.2).
GiNaC::ex force_power(const Kinematics& kin, const Vec3& x, const Vec3& F) {
  const std::vector<Vec3> J = symbolic::point_jacobian(kin, x);
  GiNaC::ex p = 0;
  for (size_t k = 0; k < J.size(); ++k) p += symbolic::dot(J[k], F) * kin.v[k];
  return p;
}

}  // namespace

// The same virtual work as symbolic::add_generalized_forces and the torques of
// add_body_terms, each source dotted with v instead of summed into Q.
std::vector<PowerSource> power_sources(const Equations& eq) {
  const Model& model = *eq.model;
  const Kinematics& kin = eq.kin;
  std::vector<PowerSource> out;
  std::map<std::string, size_t> index;
  const auto add = [&](const std::string& name, const GiNaC::ex& power) {
    if (power.is_zero()) return;
    const auto [it, fresh] = index.emplace(name, out.size());
    if (fresh)
      out.push_back({name, power});
    else
      out[it->second].power += power;
  };
  for (const PointForce& f : model.forces)
    if (const Point* x = model.find_point(f.point); x != nullptr)
      add("force at '" + f.point + "'" + at_line(f.loc), force_power(kin, x->pos, f.force));
  for (const BodyTorque& tq : model.torques) {
    const Body* body = model.find_body(tq.body);
    if (body == nullptr) continue;
    // τ·ω_world = (Rᵀτ)·ω (docs/theory.md §4.4)
    const Vec3 tb = tq.body_frame ? tq.torque : model::mat_t_vec(body->rot(), tq.torque);
    add("torque on '" + tq.body + "'" + at_line(tq.loc),
        symbolic::dot(tb, symbolic::body_angular_velocity(kin, *body)));
  }
  for (const Damper& d : model.dampers) {
    const Point* a = model.find_point(d.a);
    const Point* b = model.find_point(d.b);
    if (a == nullptr || b == nullptr) continue;
    const Vec3 r = model::sub(b->pos, a->pos);
    const GiNaC::ex dist = GiNaC::sqrt(symbolic::dot(r, r));
    const GiNaC::ex rate = symbolic::derivative_without_accelerations(kin, dist);
    const std::vector<GiNaC::ex> ddq = symbolic::velocity_gradient(kin, dist);
    GiNaC::ex p = 0;
    for (size_t k = 0; k < ddq.size(); ++k) p -= d.c * rate * ddq[k] * kin.v[k];
    add("damper '" + d.a + "'–'" + d.b + "'" + at_line(d.loc), p);
  }
  for (size_t i = 0; i < model.coordinates.size() && i < model.generalized_forces.size(); ++i)
    add("generalised force on '" + model.coordinates[i].name + "'",
        model.generalized_forces[i] * kin.v[i]);
  return out;
}

// docs/theory.md §10, "Checks": H = Σ vᵢ ∂L/∂vᵢ − L.
GiNaC::ex energy_function(const Equations& eq) {
  const GiNaC::ex L = eq.T - eq.U;
  symbolic::MemoDiff d(eq.kin.v);
  GiNaC::ex H = -L;
  for (size_t k : d.columns_in(L)) H += eq.kin.v[k] * d.diff(L, k);
  return H;
}

std::string energy_balance_unsuitable(const Equations& eq) {
  const Model& model = *eq.model;
  std::vector<GiNaC::symbol> watched{model.t};
  std::vector<std::string> names{"t"};
  for (const Input& u : model.inputs)
    for (const GiNaC::symbol& s : {u.u, u.ud, u.udd}) {
      watched.push_back(s);
      names.push_back("the input '" + u.name + "'");
    }
  symbolic::MemoDiff scan(watched);
  const auto first = [&](const GiNaC::ex& e) -> std::string {
    const std::vector<size_t>& in = scan.columns_in(e);
    return in.empty() ? "" : names[in.front()];
  };
  if (std::string s = first(eq.T - eq.U); !s.empty())
    return "the energies depend on " + s + ", whose driver does work";
  for (size_t i = 0; i < eq.C.size(); ++i)
    if (std::string s = first(eq.C[i]); !s.empty())
      return "constraint '" + model.constraints.at(i).name + "' depends on " + s +
             ", whose driver does work";
  return "";
}

double EnergyBalance::relative_residual() const {
  const double s = std::max(std::fabs(change), scale);
  return s > 0 ? std::fabs(residual) / s : 0.0;
}

}  // namespace lagrange
