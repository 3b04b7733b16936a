#pragma once
// Turning SUNDIALS return flags and NaNs into lagrange::SimulationError.

#include <cstddef>
#include <string>

namespace lagrange::integration {

/// A package's flag-to-name function, e.g. CVodeGetReturnFlagName (its result is malloc'ed).
using FlagNameFn = char* (*)(long int);

/// Keeps the last error message a SUNDIALS solver reported instead of printing it to stderr.
class ErrorLog {
 public:
  /// Error-handler callback (ARKErrHandlerFn / CVErrHandlerFn / IDAErrHandlerFn); `self` is this.
  static void handler(int code, const char* module, const char* function, char* msg,
                      void* self) noexcept;
  /// The last error message since the previous take(), or "" (and forgets it). Not matched by
  /// code: IDA 6.4 reports IDA_TOO_MUCH_WORK to the handler as code -22.
  std::string take();

 private:
  std::string message_;
};

/// The symbolic name of a SUNDIALS return flag, e.g. "CV_TOO_MUCH_WORK".
std::string flag_name(FlagNameFn name_of, int flag);

/// Throws SimulationError(t, "<call> failed with <FLAG> (flag <n>): <message>") when flag < 0;
/// `t` is the time the solver reached, `log` (may be null) supplies SUNDIALS' own explanation
/// and is cleared on every call so a message never outlives the call that caused it.
void check(int flag, const char* call, FlagNameFn name_of, double t, ErrorLog* log);

/// SUNDIALS' mxstep for one-step mode, which does not apply it: at most `max_steps` internal steps
/// toward one output sample.
class StepBudget {
 public:
  explicit StepBudget(long max_steps) : max_steps_(max_steps) {}
  /// Counts one more step toward the sample at t_next (from time t); past the budget throws
  /// SimulationError(t, "<call> failed with <flag>: mxstep steps taken (<n>) before reaching the
  /// output sample at t = <t_next>").
  void spend(double t_next, double t, const char* call, const char* flag);

 private:
  long max_steps_;
  long taken_ = 0;
  double target_ = 0.0;
};

/// Throws SimulationError(t, …) naming the first NaN/Inf among v[0..n), reported as `what[i]`.
void ensure_finite(double t, const double* v, size_t n, const char* what);

}  // namespace lagrange::integration
