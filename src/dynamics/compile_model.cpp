#include "lagrange/compiled_model.hpp"

namespace lagrange {

std::shared_ptr<const CompiledModel> compile(const Equations& eq) {
  const Model& model = *eq.model;
  auto cm = std::make_shared<CompiledModel>();
  cm->n = eq.n;
  cm->m = eq.m;
  cm->k = model.inputs.size();
  cm->np = model.parameters.size();
  for (const auto& c : model.coordinates) {
    cm->coordinate_names.push_back(c.name);
    cm->q0.push_back(c.initial);
    cm->v0.push_back(c.rate);
    cm->fixed.push_back(c.fixed);
  }
  for (const auto& c : model.constraints) cm->constraint_names.push_back(c.name);
  for (const auto& o : model.outputs) cm->output_names.push_back(o.name);
  for (const auto& u : model.inputs) cm->input_names.push_back(u.name);
  for (const auto& p : model.parameters) {
    cm->parameter_names.push_back(p.name);
    cm->parameter_defaults.push_back(p.value);
  }

  std::vector<GiNaC::ex> dyn;
  cm->M_diagonal = true;
  for (size_t i = 0; i < eq.n; ++i)
    for (size_t j = 0; j <= i; ++j)
      if (!eq.M(i, j).is_zero()) {
        cm->M_pattern.emplace_back(i, j);
        dyn.push_back(eq.M(i, j));
        if (i != j) cm->M_diagonal = false;
      }
  for (size_t i = 0; i < eq.n; ++i) dyn.push_back(eq.h[i] + eq.Q[i]);
  for (size_t i = 0; i < eq.n; ++i) dyn.push_back(eq.qdot[i]);
  for (size_t r = 0; r < eq.m; ++r)
    for (size_t j = 0; j < eq.n; ++j)
      if (!eq.G(r, j).is_zero()) {
        cm->G_pattern.emplace_back(r, j);
        dyn.push_back(eq.G(r, j));
      }
  for (const auto& e : eq.c) dyn.push_back(e);
  for (const auto& e : eq.Cdot) dyn.push_back(e);
  for (const auto& e : eq.C) dyn.push_back(e);

  const std::vector<GiNaC::symbol> in = eq.tape_inputs();
  cm->dynamics = Tape::compile(dyn, in);

  std::vector<GiNaC::ex> obs{eq.T, eq.U};
  for (const auto& e : eq.outputs) obs.push_back(e);
  cm->observables = Tape::compile(obs, in);

  std::vector<GiNaC::ex> sig;
  for (const auto& u : model.inputs) sig.push_back(u.expr);
  for (const auto& u : model.inputs) sig.push_back(u.expr.diff(model.t));
  for (const auto& u : model.inputs) sig.push_back(u.expr.diff(model.t, 2));
  cm->inputs = Tape::compile(sig, in);
  return cm;
}

}  // namespace lagrange
