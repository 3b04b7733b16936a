#include "lagrange/equations.hpp"
#include "symbolic/mechanical_terms.hpp"

namespace lagrange {

Equations derive(const Model& model) {
  const size_t n = model.coordinates.size();
  symbolic::MechanicalTerms terms(n);
  symbolic::add_particle_terms(model, terms);
  symbolic::add_energy_terms(model, terms);
  symbolic::add_generalized_forces(model, terms);

  Equations eq;
  eq.model = &model;
  eq.n = n;
  eq.T = terms.T;
  eq.U = terms.U;
  eq.L = terms.T - terms.U;
  eq.M = terms.M;
  eq.h = std::move(terms.h);
  eq.Q = std::move(terms.Q);
  for (const auto& c : model.coordinates) eq.qdot.push_back(c.v);
  symbolic::add_constraint_terms(model, eq);
  for (const auto& out : model.outputs) eq.outputs.push_back(out.expr);
  return eq;
}

GiNaC::ex Equations::euler_lagrange_lhs(size_t i) const {
  GiNaC::ex lhs = -h[i];
  for (size_t j = 0; j < n; ++j) lhs += M(i, j) * model->coordinates[j].a;
  return lhs;
}

std::vector<GiNaC::symbol> Equations::tape_inputs() const {
  std::vector<GiNaC::symbol> in{model->t};
  for (const auto& c : model->coordinates) in.push_back(c.q);
  for (const auto& c : model->coordinates) in.push_back(c.v);
  for (const auto& u : model->inputs) in.push_back(u.u);
  for (const auto& u : model->inputs) in.push_back(u.ud);
  for (const auto& u : model->inputs) in.push_back(u.udd);
  for (const auto& p : model->parameters) in.push_back(p.sym);
  return in;
}

std::vector<GiNaC::ex> solve_accelerations(const Equations& eq) {
  if (eq.m > 0) throw std::invalid_argument("solve_accelerations: the system is constrained");
  if (eq.n > 4) throw std::invalid_argument("solve_accelerations: more than 4 coordinates");
  GiNaC::matrix rhs(static_cast<unsigned>(eq.n), 1);
  for (size_t i = 0; i < eq.n; ++i) rhs(i, 0) = eq.h[i] + eq.Q[i];
  GiNaC::matrix a = eq.M.inverse().mul(rhs);
  std::vector<GiNaC::ex> out;
  for (size_t i = 0; i < eq.n; ++i) out.push_back(a(i, 0).normal());
  return out;
}

}  // namespace lagrange
