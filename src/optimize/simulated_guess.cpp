#include "optimize/simulated_guess.hpp"

#include <algorithm>

#include "lagrange/simulation.hpp"

namespace lagrange::collocation {

std::vector<std::vector<double>> simulated_states(Dynamics& dyn, const std::vector<size_t>& inputs,
                                                  const std::vector<double>& values,
                                                  const std::vector<double>& q0,
                                                  const std::vector<double>& v0,
                                                  const std::vector<double>& times) {
  if (times.empty()) return {};
  double gap = times.back();
  for (size_t i = 1; i < times.size(); ++i)
    if (times[i] > times[i - 1]) gap = std::min(gap, times[i] - times[i - 1]);
  for (size_t c = 0; c < inputs.size(); ++c) dyn.hold_input(inputs[c], values[c]);
  SimulationOptions so;
  so.t_end = times.back();
  so.output_step = gap / 8;
  const Trajectory traj = simulate(dyn, so, q0, v0);
  if (traj.status != Trajectory::Status::Complete || traj.rows() < 2) return {};
  const size_t cols = traj.columns.size(), nx = q0.size() + v0.size();
  std::vector<std::vector<double>> out;
  size_t r = 0;
  for (double t : times) {
    while (r + 2 < traj.rows() && traj.data[(r + 1) * cols] < t) ++r;
    const double t0 = traj.data[r * cols], t1 = traj.data[(r + 1) * cols];
    const double s = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
    std::vector<double> x(nx);
    for (size_t i = 0; i < nx; ++i)
      x[i] = (1 - s) * traj.data[r * cols + 1 + i] + s * traj.data[(r + 1) * cols + 1 + i];
    out.push_back(std::move(x));
  }
  return out;
}

}  // namespace lagrange::collocation
