#include "optimize/simulated_guess.hpp"

#include <algorithm>

#include "lagrange/simulation.hpp"

namespace lagrange::collocation {

SimulatedGuess simulated_states(Dynamics& dyn, const std::vector<size_t>& inputs,
                                const std::vector<std::optional<double>>& held,
                                const std::vector<double>& q0, const std::vector<double>& v0,
                                const std::vector<double>& times) {
  if (times.empty()) return {};
  double gap = times.back();
  for (size_t i = 1; i < times.size(); ++i)
    if (times[i] > times[i - 1]) gap = std::min(gap, times[i] - times[i - 1]);
  dyn.release_inputs();
  for (size_t c = 0; c < inputs.size(); ++c)
    if (held[c]) dyn.hold_input(inputs[c], *held[c]);
  SimulationOptions so;
  so.t_end = times.back();
  so.output_step = gap / 8;
  const Trajectory traj = simulate(dyn, so, q0, v0);
  if (traj.status != Trajectory::Status::Complete || traj.rows() < 2) return {};
  const size_t cols = traj.columns.size(), nq = q0.size(), nx = nq + v0.size();
  const size_t u_at = dyn.model().u_offset();
  std::vector<double> C(dyn.model().m + 1), Cdot(dyn.model().m + 1);
  SimulatedGuess out;
  size_t r = 0;
  for (double t : times) {
    while (r + 2 < traj.rows() && traj.data[(r + 1) * cols] < t) ++r;
    const double t0 = traj.data[r * cols], t1 = traj.data[(r + 1) * cols];
    const double s = std::clamp((t - t0) / (t1 - t0), 0.0, 1.0);
    std::vector<double> x(nx);
    for (size_t i = 0; i < nx; ++i)
      x[i] = (1 - s) * traj.data[r * cols + 1 + i] + s * traj.data[(r + 1) * cols + 1 + i];
    // The inputs as the dynamics evaluate them there: held values or the declared expressions.
    dyn.constraints(t, x.data(), x.data() + nq, C.data(), Cdot.data());
    std::vector<double> u;
    for (size_t c : inputs) u.push_back(dyn.last_inputs()[u_at + c]);
    out.states.push_back(std::move(x));
    out.controls.push_back(std::move(u));
  }
  return out;
}

}  // namespace lagrange::collocation
