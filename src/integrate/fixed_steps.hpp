#pragma once
// The grid walk of the fixed-step methods (RK4, implicit midpoint): an integer number of equal
// steps per output interval.

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "integrate/walk_grid.hpp"

namespace lagrange::integration {

/// Each output interval gets ceil(length / step) equal steps (step = options.step, or the output
/// step / 10; the 1e-9 absorbs rounding); `step(t, h)` advances y by one of them, then
/// options.after_step sees y (the last one before the observer). More than options.max_steps
/// steps in one interval is std::invalid_argument.
template <class Step>
void walk_fixed_steps(const OutputGrid& grid, const IntegratorOptions& options,
                      const Observer& observer, std::vector<double>& y, Step&& step) {
  const double nominal = options.step > 0.0 ? options.step : grid.step() / 10.0;
  double t_now = grid.time(0);
  const auto advance = [&](double t_next) {
    const double length = t_next - t_now;
    const double steps = std::ceil(length / nominal - 1e-9);
    if (!(steps <= static_cast<double>(options.max_steps)))  // also keeps the cast in range
      throw std::invalid_argument(
          fmt::format("integrator: the fixed step {} makes {:.3g} steps in an output interval of "
                      "{}, more than max_steps = {}",
                      nominal, steps, length, options.max_steps));
    const long count = std::max(1L, static_cast<long>(steps));
    const double h = length / static_cast<double>(count);
    for (long i = 0; i < count; ++i) {
      step(t_now + static_cast<double>(i) * h, h);
      if (options.after_step) options.after_step(t_now + static_cast<double>(i + 1) * h, y.data());
    }
    t_now = t_next;
  };
  const auto restart = [](double) {};  // a one-step method keeps no history
  walk_grid(grid, observer, y.data(), nullptr, advance, restart);
}

}  // namespace lagrange::integration
