#include "optimize/point_functions.hpp"

#include "symbolic/memo_diff.hpp"

namespace lagrange::collocation {

std::vector<GiNaC::ex> problem_functions(const OptimalControlSpec& spec) {
  std::vector<GiNaC::ex> fs{spec.integrand, spec.terminal, spec.mean_integrand};
  for (const PathConstraintSpec& p : spec.path) fs.push_back(p.expr);
  return fs;
}

// Memoised over the expressions' shared subtrees (symbolic/memo_diff.hpp): GiNaC's diff walked
// them again per row and column, and threw and caught an exception at every function node it
// met (its chain rule's fallback), which took the Panda's set-up to 22 s (docs/benchmarks.md).
std::vector<std::pair<size_t, size_t>> append_derivatives(const std::vector<GiNaC::ex>& fs,
                                                          const std::vector<GiNaC::symbol>& in,
                                                          const std::vector<size_t>& columns,
                                                          std::vector<GiNaC::ex>& outputs) {
  symbolic::MemoDiff d(in, columns);
  std::vector<std::pair<size_t, size_t>> pattern;
  for (size_t i = 0; i < fs.size(); ++i)
    for (size_t c : d.columns_in(fs[i])) {
      const GiNaC::ex di = d.diff(fs[i], c);
      if (di.is_zero()) continue;
      pattern.emplace_back(i, c);
      outputs.push_back(di);
    }
  return pattern;
}

PointFunctions::PointFunctions(const Equations& eq, const CompiledModel& cm,
                               const std::vector<GiNaC::ex>& fs,
                               const std::vector<size_t>& controls,
                               const std::vector<GiNaC::symbol>& multipliers)
    : count_(fs.size()), multipliers_(multipliers.size()) {
  std::vector<GiNaC::symbol> in = eq.tape_inputs();
  std::vector<size_t> columns{0};  // input of each column: t, q, v, the controls, then λ
  for (size_t i = 0; i < cm.nq + cm.nv; ++i) columns.push_back(cm.q_offset() + i);
  for (size_t j : controls) columns.push_back(cm.u_offset() + j);
  for (const GiNaC::symbol& l : multipliers) {
    columns.push_back(in.size());
    in.push_back(l);
  }
  std::vector<GiNaC::ex> outputs(fs.begin(), fs.end());
  pattern_ = append_derivatives(fs, in, columns, outputs);
  tape_ = Tape::compile(outputs, in);
  work_.resize(std::max<size_t>(tape_.work_size(), 1));
}

void PointFunctions::eval(const std::vector<double>& in, const double* lambda,
                          std::vector<double>& out) const {
  out.resize(tape_.num_outputs());
  in_.assign(in.begin(), in.end());
  if (multipliers_ > 0) in_.insert(in_.end(), lambda, lambda + multipliers_);
  tape_.eval(in_.data(), out.data(), work_.data());
}

}  // namespace lagrange::collocation
