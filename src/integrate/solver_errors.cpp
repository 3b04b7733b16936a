#include "integrate/solver_errors.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <memory>

#include "lagrange/error.hpp"

namespace lagrange::integration {

void ErrorLog::handler(int code, const char* /*module*/, const char* function, char* msg,
                       void* self) noexcept {
  if (code >= 0) return;  // warnings are not failures; stay silent
  auto* log = static_cast<ErrorLog*>(self);
  try {  // called from C: nothing may escape
    log->message_ = fmt::format("{}: {}", function ? function : "?", msg ? msg : "");
  } catch (...) {
    log->message_.clear();
  }
}

std::string ErrorLog::take() {
  std::string message;
  message.swap(message_);
  return message;
}

std::string flag_name(FlagNameFn name_of, int flag) {
  std::unique_ptr<char, decltype(&std::free)> name(name_of(flag), &std::free);
  return name ? std::string(name.get()) : fmt::format("flag {}", flag);
}

void check(int flag, const char* call, FlagNameFn name_of, double t, ErrorLog* log) {
  const std::string detail = log ? log->take() : "";
  if (flag >= 0) return;
  std::string what =
      fmt::format("{} failed with {} (flag {})", call, flag_name(name_of, flag), flag);
  if (!detail.empty()) what += ": " + detail;
  throw SimulationError(t, what);
}

void StepBudget::spend(double t_next, double t, const char* call, const char* flag) {
  if (t_next != target_) {
    target_ = t_next;
    taken_ = 0;
  }
  if (++taken_ <= max_steps_) return;
  throw SimulationError(t, fmt::format("{} failed with {}: mxstep steps taken ({}) before reaching "
                                       "the output sample at t = {}",
                                       call, flag, max_steps_, t_next));
}

void ensure_finite(double t, const double* v, size_t n, const char* what) {
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) {
      throw SimulationError(t, fmt::format("{}[{}] = {} is not finite", what, i, v[i]));
    }
  }
}

}  // namespace lagrange::integration
