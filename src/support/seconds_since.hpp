#pragma once
// The wall time every timed stage reports (set-up, solve, compile, a sweep's case).

#include <chrono>

namespace lagrange {

/// Seconds on the steady clock since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace lagrange
