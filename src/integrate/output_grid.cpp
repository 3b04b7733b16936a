#include "integrate/output_grid.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "lagrange/integrator.hpp"

namespace lagrange::integration {

OutputGrid::OutputGrid(double t0, double t_end, double dt) : t0_(t0), t_end_(t_end), dt_(dt) {
  if (!std::isfinite(t0) || !std::isfinite(t_end) || !std::isfinite(dt)) {
    throw std::invalid_argument(
        fmt::format("output grid: expected finite t0, t_end, dt, got {}, {}, {}", t0, t_end, dt));
  }
  if (!(dt > 0.0)) {
    throw std::invalid_argument(fmt::format("output grid: expected dt > 0, got {}", dt));
  }
  if (t_end < t0) {
    throw std::invalid_argument(
        fmt::format("output grid: expected t_end >= t0, got t0 = {}, t_end = {}", t0, t_end));
  }
  const double ratio = (t_end - t0) / dt;
  if (!(ratio <= kMaxOutputIntervals))  // also keeps the casts below in range
    throw std::invalid_argument(
        fmt::format("output grid: (t_end - t0) / dt = {:.3g} intervals, more than the {:.0e} a "
                    "run may keep (t0 = {}, t_end = {}, dt = {})",
                    ratio, kMaxOutputIntervals, t0, t_end, dt));
  const double nearest = std::round(ratio);
  if (std::abs(ratio - nearest) <= 1e-9 * std::max(1.0, ratio)) {
    intervals_ = static_cast<size_t>(nearest);
  } else {
    intervals_ = static_cast<size_t>(std::floor(ratio)) + 1;
  }
  if (intervals_ == 0 && t_end > t0) intervals_ = 1;  // t_end barely past t0 still gets a sample
}

double OutputGrid::time(size_t k) const {
  k += first_;
  return k >= intervals_ ? t_end_ : t0_ + static_cast<double>(k) * dt_;
}

OutputGrid OutputGrid::from(size_t k) const {
  if (k > intervals())
    throw std::out_of_range(
        fmt::format("output grid: sample {} of a grid of {} intervals", k, intervals()));
  OutputGrid rest = *this;
  rest.first_ += k;
  return rest;
}

}  // namespace lagrange::integration
