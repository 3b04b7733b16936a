#include "optimize/invariant_jacobian.hpp"

#include <algorithm>

namespace lagrange::collocation {

InvariantJacobian::InvariantJacobian(const Equations& eq, const CompiledModel& cm) {
  if (cm.m == 0) return;
  const std::vector<GiNaC::ex> out = dynamics_expressions(eq, cm);
  const std::vector<GiNaC::symbol> in = eq.tape_inputs();
  std::vector<GiNaC::ex> gradients;
  for (size_t i = 0; i < 2 * cm.m; ++i) {
    const GiNaC::ex& f = i < cm.m ? out[cm.C_out() + i] : out[cm.Cdot_out() + i - cm.m];
    for (size_t c = 0; c < cm.nq + cm.nv; ++c) {
      const GiNaC::symbol& x = in[cm.q_offset() + c];
      if (!f.has(x)) continue;
      const GiNaC::ex d = f.diff(x);
      if (d.is_zero()) continue;
      pattern_.emplace_back(i, c);
      gradients.push_back(d);
    }
  }
  tape_ = Tape::compile(gradients, in);
  work_.resize(std::max<size_t>(tape_.work_size(), 1));
}

void InvariantJacobian::eval(const double* in, std::vector<double>& out) const {
  out.resize(tape_.num_outputs());
  if (!pattern_.empty()) tape_.eval(in, out.data(), work_.data());
}

}  // namespace lagrange::collocation
