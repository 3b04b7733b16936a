#include "optimize/point_residual.hpp"

#include <algorithm>
#include <string>

#include "optimize/point_functions.hpp"

namespace lagrange::collocation {

std::vector<GiNaC::symbol> numbered_symbols(const std::string& name, size_t count) {
  std::vector<GiNaC::symbol> out;
  for (size_t i = 0; i < count; ++i) out.emplace_back(name + std::to_string(i));
  return out;
}

ResidualSymbols::ResidualSymbols(size_t nv, size_t m)
    : a(numbered_symbols("dae_a", nv)), lambda(numbered_symbols("dae_l", m)), alpha("dae_alpha") {}

// docs/theory.md §4.3: M and G from their stored patterns (M's upper triangle), as
// Dynamics::dae_residual evaluates them.
std::vector<GiNaC::ex> residual_rows(const Equations& eq, const CompiledModel& cm,
                                     const ResidualSymbols& s) {
  const std::vector<GiNaC::ex> out = dynamics_expressions(eq, cm);
  const size_t nq = cm.nq, nv = cm.nv;
  std::vector<GiNaC::ex> rho(nq + nv + cm.m);
  for (size_t i = 0; i < nq; ++i) rho[i] = -out[cm.qdot_out() + i];
  for (size_t i = 0; i < nv; ++i) rho[nq + i] = -out[cm.rhs_out() + i];
  for (size_t e = 0; e < cm.M_pattern.size(); ++e) {
    const auto [i, j] = cm.M_pattern[e];
    rho[nq + i] += out[e] * s.a[j];
    if (i != j) rho[nq + j] += out[e] * s.a[i];
  }
  for (size_t k = 0; k < cm.m; ++k)
    rho[nq + nv + k] = out[cm.c_out() + k] + 2 * s.alpha * out[cm.Cdot_out() + k] +
                       s.alpha * s.alpha * out[cm.C_out() + k];
  for (size_t e = 0; e < cm.G_pattern.size(); ++e) {
    const auto [k, j] = cm.G_pattern[e];
    rho[nq + j] += out[cm.G_out() + e] * s.lambda[k];
    rho[nq + nv + k] += out[cm.G_out() + e] * s.a[j];
  }
  return rho;
}

PointResidual::PointResidual(const Equations& eq, const CompiledModel& cm,
                             const std::vector<size_t>& controls, Evaluation mode,
                             const MachineCodeOptions& options) {
  const ResidualSymbols s(cm.nv, cm.m);
  const std::vector<GiNaC::ex> rho = residual_rows(eq, cm, s);
  rows_ = rho.size();
  std::vector<GiNaC::symbol> in = eq.tape_inputs();
  std::vector<size_t> columns;  // tape input of each column: q, v, the controls, a, λ
  for (size_t i = 0; i < cm.nq + cm.nv; ++i) columns.push_back(cm.q_offset() + i);
  for (size_t c : controls) columns.push_back(cm.u_offset() + c);
  for (const std::vector<GiNaC::symbol>* group : {&s.a, &s.lambda})
    for (const GiNaC::symbol& x : *group) {
      columns.push_back(in.size());
      in.push_back(x);
    }
  in.push_back(s.alpha);
  std::vector<GiNaC::ex> outputs = rho;
  pattern_ = append_derivatives(rho, in, columns, outputs);
  tape_ = MachineTape(Tape::compile(outputs, in));
  // Evaluated at every point for the constraints and the Jacobian: after the Hessian's, the
  // costliest tape of the solve (docs/theory.md §10, "Evaluating the NLP").
  if (mode != Evaluation::Interpreter) tape_.use_machine_code(mode, options);
}

}  // namespace lagrange::collocation
