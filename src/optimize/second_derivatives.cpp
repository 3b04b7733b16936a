#include "optimize/second_derivatives.hpp"

#include <algorithm>

#include "dynamics/native_tapes.hpp"
#include "symbolic/memo_diff.hpp"

namespace lagrange::collocation {

SecondDerivatives::SecondDerivatives() = default;
SecondDerivatives::SecondDerivatives(SecondDerivatives&&) noexcept = default;
SecondDerivatives& SecondDerivatives::operator=(SecondDerivatives&&) noexcept = default;
SecondDerivatives::~SecondDerivatives() = default;

// Both differentiations memoised over the expression DAG (symbolic/memo_diff.hpp): GiNaC's own
// diff walked the weighted residual's shared subtrees again for every column and pair, 3.5 s of
// the AP2's 3.8 s set-up (docs/benchmarks.md).
SecondDerivatives::SecondDerivatives(const GiNaC::ex& s, const std::vector<GiNaC::symbol>& inputs,
                                     const std::vector<size_t>& columns) {
  std::vector<GiNaC::symbol> column_symbols;
  for (size_t c : columns) column_symbols.push_back(inputs.at(c));
  symbolic::MemoDiff d(column_symbols);
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
  tape_ = Tape::compile(outputs, inputs);
  work_.resize(std::max<size_t>(tape_.work_size(), 1));
}

void SecondDerivatives::use_machine_code(Evaluation mode, const MachineCodeOptions& options) {
  if (!native_) native_ = std::make_unique<dynamics::NativeTapes>();
  native_->mode = mode;
  native_->options = options;
  native_->start({&tape_});
}

std::string SecondDerivatives::evaluation_note() const {
  return native_ ? native_->note() : "interpreter";
}

void SecondDerivatives::eval(const std::vector<double>& in, std::vector<double>& out) const {
  out.resize(tape_.num_outputs());
  if (native_)
    if (const MachineCode::Function f = native_->function(0)) {
      f(in.data(), out.data(), work_.data());
      return;
    }
  tape_.eval(in.data(), out.data(), work_.data());
}

}  // namespace lagrange::collocation
