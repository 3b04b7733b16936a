#include <stdexcept>

#include "lagrange/compiled_model.hpp"

namespace lagrange {

std::vector<GiNaC::ex> dynamics_expressions(const Equations& eq, const CompiledModel& cm) {
  std::vector<GiNaC::ex> dyn;
  for (const auto& [i, j] : cm.M_pattern) dyn.push_back(eq.M(i, j));
  for (size_t i = 0; i < eq.nv; ++i) dyn.push_back(eq.h[i] + eq.Q[i]);
  for (size_t i = 0; i < eq.nq; ++i) dyn.push_back(eq.qdot[i]);
  for (const auto& [r, j] : cm.G_pattern) dyn.push_back(eq.G(r, j));
  for (const auto& e : eq.c) dyn.push_back(e);
  for (const auto& e : eq.Cdot) dyn.push_back(e);
  for (const auto& e : eq.C) dyn.push_back(e);
  for (const auto& [r, j] : cm.Cq_pattern) dyn.push_back(eq.Cq(r, j));
  return dyn;
}

ModelInitialState model_initial_state(const Model& model) {
  ModelInitialState s;
  for (const auto& c : model.coordinates) {
    s.q0.push_back(c.initial);
    s.fixed.push_back(c.fixed);
  }
  for (const auto& c : model.coordinates) s.v0.push_back(c.rate);
  for (const auto& b : model.bodies) {  // free bodies, in the order of kinematics()
    if (!b.free) continue;
    s.q0.insert(s.q0.end(), b.r0.begin(), b.r0.end());
    s.rotations.push_back(s.q0.size());
    s.q0.insert(s.q0.end(), b.R0.begin(), b.R0.end());
    s.fixed.insert(s.fixed.end(), 12, false);
    s.v0.insert(s.v0.end(), b.v0.begin(), b.v0.end());
    s.v0.insert(s.v0.end(), b.w0.begin(), b.w0.end());
  }
  return s;
}

namespace {

// docs/theory.md §4.11: a load is linear in a and λ; its coefficients join the observables
// (appended to `obs`), and the row writer sums them with the solved a and λ.
std::vector<LoadColumn> load_columns(const Model& model, std::vector<GiNaC::ex>& obs) {
  std::vector<LoadColumn> columns;
  for (const Load& load : model.loads) {
    LoadColumn column{load.name, {}};
    for (const LoadPart& part : load.parts) {
      std::vector<LoadTerm> terms;
      GiNaC::exmap zero;
      for (size_t i = 0; i < model.coordinates.size(); ++i) {
        const GiNaC::symbol& a = model.coordinates[i].a;
        if (!part.expr.has(a)) continue;
        zero[a] = 0;
        terms.push_back(LoadTerm{obs.size(), static_cast<int>(i), -1});
        obs.push_back(part.expr.diff(a));
      }
      for (const LoadTerm& term : terms)
        for (const auto& [sym, unused] : zero)
          if (obs[term.observable].has(sym))
            throw std::logic_error("load '" + load.name + "' is not linear in the accelerations");
      terms.push_back(LoadTerm{obs.size(), -1, -1});
      obs.push_back(part.expr.subs(zero));
      for (const auto& [c, coefficient] : part.multipliers) {
        terms.push_back(LoadTerm{obs.size(), -1, static_cast<int>(c)});
        obs.push_back(coefficient);
      }
      column.parts.push_back(std::move(terms));
    }
    columns.push_back(std::move(column));
  }
  return columns;
}

}  // namespace

std::shared_ptr<const CompiledModel> compile(const Equations& eq) {
  const Model& model = *eq.model;
  auto cm = std::make_shared<CompiledModel>();
  const Kinematics& kin = eq.kin;
  cm->nq = eq.nq;
  cm->nv = eq.nv;
  cm->plain = kin.plain;
  cm->m = eq.m;
  cm->k = model.inputs.size();
  cm->coordinate_names = kin.q_names;
  cm->velocity_names = kin.v_names;
  ModelInitialState initial = model_initial_state(model);
  cm->q0 = std::move(initial.q0);
  cm->v0 = std::move(initial.v0);
  cm->fixed = std::move(initial.fixed);
  cm->rotations = std::move(initial.rotations);
  for (const auto& c : model.constraints) cm->constraint_names.push_back(c.name);
  for (const auto& r : model.reactions) {
    cm->reaction_names.push_back(r.name);
    cm->reaction_constraints.push_back(r.constraint);
  }
  cm->output_names = eq.output_names;
  cm->stop_when = model.stop_when;
  cm->fail_when = model.fail_when;
  cm->warn_when = model.warn_when;
  cm->conservative = conserves_energy(eq);
  for (const auto& u : model.inputs) {
    cm->input_names.push_back(u.name);
    cm->external_inputs.push_back(u.external);
  }
  for (const auto& p : model.parameters) {
    cm->parameter_names.push_back(p.name);
    cm->parameter_defaults.push_back(p.value);
  }
  if (kin.has_gamma) {
    cm->parameter_names.push_back("stabilization.gamma");
    cm->parameter_defaults.push_back(model.stabilization.gamma);
  }
  cm->np = cm->parameter_names.size();

  cm->M_diagonal = true;
  for (size_t i = 0; i < eq.nv; ++i)
    for (size_t j = 0; j <= i; ++j)
      if (!eq.M(i, j).is_zero()) {
        cm->M_pattern.emplace_back(i, j);
        if (i != j) cm->M_diagonal = false;
      }
  for (size_t r = 0; r < eq.m; ++r)
    for (size_t j = 0; j < eq.nv; ++j)
      if (!eq.G(r, j).is_zero()) cm->G_pattern.emplace_back(r, j);
  for (size_t r = 0; r < eq.m; ++r)
    for (size_t j = 0; j < eq.nq; ++j)
      if (!eq.Cq(r, j).is_zero()) cm->Cq_pattern.emplace_back(r, j);
  const std::vector<GiNaC::ex> dyn = dynamics_expressions(eq, *cm);

  const std::vector<GiNaC::symbol> in = eq.tape_inputs();
  cm->dynamics = Tape::compile(dyn, in, eq.definitions);

  std::vector<GiNaC::ex> obs{eq.T, eq.U};
  for (const auto& e : eq.outputs) obs.push_back(e);
  for (const auto& e : eq.reaction_scales) obs.push_back(e);
  cm->loads = load_columns(model, obs);
  cm->observables = Tape::compile(obs, in, eq.definitions);

  std::vector<GiNaC::ex> sig;
  for (const auto& u : model.inputs) sig.push_back(u.expr);
  for (const auto& u : model.inputs) sig.push_back(u.expr.diff(model.t));
  for (const auto& u : model.inputs) sig.push_back(u.expr.diff(model.t, 2));
  cm->inputs = Tape::compile(sig, in);

  // The conditions' names are checked here, before any run, and no run parses them again.
  const std::vector<std::string> columns = trajectory_columns(*cm);
  cm->stop_tape = compile_conditions(cm->stop_when, *cm, columns);
  cm->fail_tape = compile_conditions(cm->fail_when, *cm, columns);
  cm->warn_tape = compile_conditions(cm->warn_when, *cm, columns);
  return cm;
}

}  // namespace lagrange
