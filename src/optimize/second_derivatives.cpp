#include "optimize/second_derivatives.hpp"

#include <algorithm>

#include "symbolic/memo_diff.hpp"

namespace lagrange::collocation {

// Both differentiations memoised over the expression DAG (symbolic/memo_diff.hpp): GiNaC's own
// diff walked the weighted residual's shared subtrees again for every column and pair, 3.5 s of
// the AP2's 3.8 s set-up (docs/benchmarks.md).
SecondDerivatives::SecondDerivatives(const GiNaC::ex& s, const std::vector<GiNaC::symbol>& inputs,
                                     const std::vector<size_t>& columns) {
  symbolic::MemoDiff d(inputs, columns);
  const std::vector<size_t> in_s = d.columns_in(s);
  std::vector<GiNaC::ex> outputs;
  for (size_t a : in_s) {
    const GiNaC::ex first = d.diff(s, a);
    const std::vector<size_t> in_first = d.columns_in(first);
    for (size_t b : in_first) {
      if (b > a) break;
      const GiNaC::ex second = d.diff(first, b);
      if (second.is_zero()) continue;
      pattern_.emplace_back(a, b);
      outputs.push_back(second);
    }
  }
  tape_ = MachineTape(Tape::compile(outputs, inputs));
}

void SecondDerivatives::eval(const std::vector<double>& in, std::vector<double>& out) const {
  out.resize(tape_.tape().num_outputs());
  tape_.eval(in.data(), out.data());
}

}  // namespace lagrange::collocation
