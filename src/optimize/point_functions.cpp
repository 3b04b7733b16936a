#include "optimize/point_functions.hpp"

namespace lagrange::collocation {

std::vector<GiNaC::ex> problem_functions(const OptimalControlSpec& spec) {
  std::vector<GiNaC::ex> fs{spec.integrand, spec.terminal, spec.mean_integrand};
  for (const PathConstraintSpec& p : spec.path) fs.push_back(p.expr);
  return fs;
}

PointFunctions::PointFunctions(const Equations& eq, const CompiledModel& cm,
                               const std::vector<GiNaC::ex>& fs,
                               const std::vector<size_t>& controls)
    : count_(fs.size()) {
  const std::vector<GiNaC::symbol> in = eq.tape_inputs();
  std::vector<size_t> columns{0};  // tape input of each column: t, q, v, then the controls
  for (size_t i = 0; i < cm.nq + cm.nv; ++i) columns.push_back(cm.q_offset() + i);
  for (size_t j : controls) columns.push_back(cm.u_offset() + j);
  std::vector<GiNaC::ex> outputs(fs.begin(), fs.end());
  for (size_t i = 0; i < fs.size(); ++i)
    for (size_t c = 0; c < columns.size(); ++c) {
      const GiNaC::ex d = fs[i].diff(in.at(columns[c]));
      if (d.is_zero()) continue;
      pattern_.emplace_back(i, c);
      outputs.push_back(d);
    }
  tape_ = Tape::compile(outputs, in);
  work_.resize(std::max<size_t>(tape_.work_size(), 1));
}

void PointFunctions::eval(const std::vector<double>& in, std::vector<double>& out) const {
  out.resize(tape_.num_outputs());
  tape_.eval(in.data(), out.data(), work_.data());
}

}  // namespace lagrange::collocation
