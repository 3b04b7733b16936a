#pragma once
// Keeps C++ exceptions from crossing SUNDIALS' C frames: a callback body runs inside run(), which
// stores any exception and returns a negative (unrecoverable) flag; the driver rethrows it once
// the SUNDIALS call has returned.

#include <exception>
#include <utility>

namespace lagrange::integration {

/// Catches exceptions thrown in callbacks and rethrows them outside the C library.
class CallbackGuard {
 public:
  /// Runs `body`; returns 0, or -1 (unrecoverable for ARKODE/CVODE/IDA) after storing its
  /// exception.
  template <class Body>
  int run(Body&& body) noexcept {
    try {
      std::forward<Body>(body)();
      return 0;
    } catch (...) {
      if (!error_) error_ = std::current_exception();
      return -1;
    }
  }

  /// Rethrows (and forgets) the first exception a callback stored, if any.
  void rethrow_pending() {
    if (!error_) return;
    std::exception_ptr error = std::move(error_);
    error_ = nullptr;
    std::rethrow_exception(error);
  }

 private:
  std::exception_ptr error_;
};

}  // namespace lagrange::integration
