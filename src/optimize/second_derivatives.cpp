#include "optimize/second_derivatives.hpp"

#include <algorithm>

#include "dynamics/native_tapes.hpp"

namespace lagrange::collocation {

SecondDerivatives::SecondDerivatives() = default;
SecondDerivatives::SecondDerivatives(SecondDerivatives&&) noexcept = default;
SecondDerivatives& SecondDerivatives::operator=(SecondDerivatives&&) noexcept = default;
SecondDerivatives::~SecondDerivatives() = default;

SecondDerivatives::SecondDerivatives(const GiNaC::ex& s, const std::vector<GiNaC::symbol>& inputs,
                                     const std::vector<size_t>& columns) {
  std::vector<GiNaC::ex> outputs;
  for (size_t a = 0; a < columns.size(); ++a) {
    const GiNaC::symbol& x = inputs.at(columns[a]);
    if (!s.has(x)) continue;
    const GiNaC::ex first = s.diff(x);
    for (size_t b = 0; b <= a; ++b) {
      const GiNaC::symbol& y = inputs.at(columns[b]);
      if (!first.has(y)) continue;
      const GiNaC::ex second = first.diff(y);
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
