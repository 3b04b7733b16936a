#pragma once
// Per-call timing shared by the forward-dynamics benchmarks (forward_speed, pinocchio_aba), so
// that both peers are timed the same way.

#include <algorithm>
#include <chrono>
#include <cstddef>

namespace lagrange::bench {

/// Random states each benchmark cycles through.
constexpr std::size_t kStates = 64;

/// Microseconds per call of f(state index), best of three timed batches of ≥ 0.2 s each.
template <class F>
double microseconds_per_call(F&& f) {
  size_t calls = 64;
  for (;;) {  // grow the batch until it takes 0.2 s
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t k = 0; k < calls; ++k) f(k % kStates);
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > 0.2) break;
    calls *= 2;
  }
  double best = 1e300;
  for (int rep = 0; rep < 3; ++rep) {
    const auto t0 = std::chrono::steady_clock::now();
    for (size_t k = 0; k < calls; ++k) f(k % kStates);
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return 1e6 * best / static_cast<double>(calls);
}

}  // namespace lagrange::bench
