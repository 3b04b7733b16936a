#include "optimize/invariant_jacobian.hpp"

#include <algorithm>

#include "optimize/point_functions.hpp"

namespace lagrange::collocation {

InvariantJacobian::InvariantJacobian(const Equations& eq, const CompiledModel& cm) {
  if (cm.m == 0) return;
  const std::vector<GiNaC::ex> out = dynamics_expressions(eq, cm);
  const std::vector<GiNaC::symbol> in = eq.tape_inputs();
  std::vector<GiNaC::ex> fs;  // C, then Ċ
  for (size_t i = 0; i < cm.m; ++i) fs.push_back(out[cm.C_out() + i]);
  for (size_t i = 0; i < cm.m; ++i) fs.push_back(out[cm.Cdot_out() + i]);
  std::vector<size_t> columns;  // q, v
  for (size_t c = 0; c < cm.nq + cm.nv; ++c) columns.push_back(cm.q_offset() + c);
  std::vector<GiNaC::ex> gradients;
  pattern_ = append_derivatives(fs, in, columns, gradients);
  tape_ = Tape::compile(gradients, in);
  work_.resize(std::max<size_t>(tape_.work_size(), 1));
}

void InvariantJacobian::eval(const double* in, std::vector<double>& out) const {
  out.resize(tape_.num_outputs());
  if (!pattern_.empty()) tape_.eval(in, out.data(), work_.data());
}

}  // namespace lagrange::collocation
