#pragma once
// The uniform output grid t_k = t0 + k·dt, k = 0..K, whose last sample is exactly t_end.

#include <cstddef>

namespace lagrange::integration {

/// Output times t0, t0 + dt, …, t_end. If (t_end − t0)/dt is an integer within 1e-9 relative,
/// K = that integer; otherwise K = floor + 1 and the last (shorter) interval ends at t_end.
class OutputGrid {
 public:
  /// Throws std::invalid_argument unless t0, t_end, dt are finite, dt > 0 and t_end >= t0.
  OutputGrid(double t0, double t_end, double dt);
  /// K, the number of intervals (the grid has K + 1 samples).
  size_t intervals() const { return intervals_ - first_; }
  /// dt, the nominal spacing (the last interval may be shorter).
  double step() const { return dt_; }
  /// t_k; time(intervals()) is exactly t_end.
  double time(size_t k) const;
  /// The grid from its sample k on (k ≤ intervals()): time(0) is this grid's t_k, bit for bit.
  OutputGrid from(size_t k) const;

 private:
  double t0_;
  double t_end_;
  double dt_;
  size_t intervals_;
  size_t first_ = 0;  ///< samples before this grid's first, kept so that times stay t0 + k·dt
};

}  // namespace lagrange::integration
