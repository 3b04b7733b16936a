#include <stdexcept>

#include "lagrange/equations.hpp"
#include "symbolic/mechanical_terms.hpp"

namespace lagrange {

Equations derive(const Model& model, Formulation form) {
  Equations eq;
  eq.kin = kinematics(model);
  const Kinematics& kin = eq.kin;
  eq.model = &model;
  eq.nq = kin.q.size();
  eq.nv = kin.v.size();
  eq.qdot = kin.qdot;
  if (form == Formulation::Recursive) {
    if (const std::string why = recursive_unsuitable(model); !why.empty())
      throw std::invalid_argument("the recursive formulation does not apply: " + why);
    eq.recursive = true;
    symbolic::add_recursive_terms(kin, eq);  // M = 1, h = a, Q = 0
    eq.M = GiNaC::ex_to<GiNaC::matrix>(GiNaC::unit_matrix(static_cast<unsigned>(eq.nv)));
    eq.Q.assign(eq.nv, 0);
    eq.L = eq.T - eq.U;
  } else {
    symbolic::MechanicalTerms terms(kin.v.size());
    symbolic::add_particle_terms(kin, terms);
    symbolic::add_body_terms(kin, terms);
    symbolic::add_energy_terms(kin, terms);
    symbolic::add_generalized_forces(kin, terms);
    eq.T = terms.T;
    eq.U = terms.U;
    eq.L = terms.T - terms.U;
    eq.M = terms.M;
    eq.h = std::move(terms.h);
    eq.Q = std::move(terms.Q);
  }
  symbolic::add_constraint_terms(kin, eq);
  for (const auto& out : model.outputs) {
    eq.outputs.push_back(out.expr);
    eq.output_names.push_back(out.name);
  }
  for (const auto& r : model.reactions) eq.reaction_scales.push_back(r.scale);
  for (const auto& b : model.bodies) {
    if (!b.free) continue;
    const Mat3 R = b.rot();
    GiNaC::ex sq = 0;  // ‖RᵀR − 1‖²_F
    for (size_t i = 0; i < 3; ++i)
      for (size_t j = 0; j < 3; ++j) {
        const GiNaC::ex e =
            R[0][i] * R[0][j] + R[1][i] * R[1][j] + R[2][i] * R[2][j] - (i == j ? 1 : 0);
        sq += e * e;
      }
    eq.outputs.push_back(GiNaC::sqrt(sq));
    eq.output_names.push_back(b.name + ".orthonormality_error");
  }
  return eq;
}

GiNaC::ex Equations::euler_lagrange_lhs(size_t i) const {
  GiNaC::ex lhs = -h[i];
  for (size_t j = 0; j < nv; ++j) lhs += M(i, j) * kin.a[j];
  return lhs;
}

std::vector<GiNaC::symbol> Equations::tape_inputs() const {
  std::vector<GiNaC::symbol> in{model->t};
  in.insert(in.end(), kin.q.begin(), kin.q.end());
  in.insert(in.end(), kin.v.begin(), kin.v.end());
  for (const auto& u : model->inputs) in.push_back(u.u);
  for (const auto& u : model->inputs) in.push_back(u.ud);
  for (const auto& u : model->inputs) in.push_back(u.udd);
  for (const auto& p : model->parameters) in.push_back(p.sym);
  if (kin.has_gamma) in.push_back(kin.gamma);
  return in;
}

}  // namespace lagrange
