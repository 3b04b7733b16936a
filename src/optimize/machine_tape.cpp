#include "optimize/machine_tape.hpp"

#include <algorithm>

#include "dynamics/native_tapes.hpp"

namespace lagrange::collocation {

MachineTape::MachineTape() = default;
MachineTape::MachineTape(Tape tape)
    : tape_(std::move(tape)), work_(std::max<size_t>(tape_.work_size(), 1)) {}
MachineTape::MachineTape(MachineTape&&) noexcept = default;
MachineTape& MachineTape::operator=(MachineTape&&) noexcept = default;
MachineTape::~MachineTape() = default;

void MachineTape::use_machine_code(Evaluation mode, const MachineCodeOptions& options) {
  if (!native_) native_ = std::make_unique<dynamics::NativeTapes>();
  native_->mode = mode;
  native_->options = options;
  native_->start({&tape_});
}

std::string MachineTape::evaluation_note() const {
  return native_ ? native_->note() : "interpreter";
}

void MachineTape::eval(const double* in, double* out) const {
  if (native_)
    if (const MachineCode::Function f = native_->function(0)) {
      f(in, out, work_.data());
      return;
    }
  tape_.eval(in, out, work_.data());
}

}  // namespace lagrange::collocation
