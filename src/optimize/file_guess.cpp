#include "optimize/file_guess.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "lagrange/report.hpp"

namespace lagrange::collocation {

FileGuess read_file_guess(const std::string& path, const CompiledModel& cm,
                          const std::vector<std::string>& control_names,
                          const std::vector<double>& times, double horizon) {
  Trajectory traj;
  try {
    traj = read_trajectory_csv(path);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(fmt::format("guess: {}", e.what()));
  }
  const size_t rows = traj.rows(), cols = traj.columns.size();
  if (rows == 0) throw std::invalid_argument(fmt::format("guess: {} has no rows", path));
  const auto column = [&](const std::string& name) -> std::optional<size_t> {
    const auto it = std::find(traj.columns.begin(), traj.columns.end(), name);
    if (it == traj.columns.end()) return std::nullopt;
    return static_cast<size_t>(it - traj.columns.begin());
  };
  std::vector<size_t> state_columns;
  for (const auto* names : {&cm.coordinate_names, &cm.velocity_names})
    for (const std::string& name : *names) {
      const std::optional<size_t> c = column(name);
      if (!c)
        throw std::invalid_argument(
            fmt::format("guess: {} has no column '{}' (a guess file needs every coordinate and "
                        "rate of the model, as simulate and optimize write them)",
                        path, name));
      state_columns.push_back(*c);
    }
  std::vector<size_t> control_columns;
  for (const std::string& name : control_names)
    if (const std::optional<size_t> c = column(name)) control_columns.push_back(*c);
  const bool with_controls = control_columns.size() == control_names.size();
  const double last = traj.data[(rows - 1) * cols];
  // The value of column c at time t of the horizon: the file's row pair around t·last/horizon.
  size_t r = 0;
  const auto at = [&](double t, size_t c) {
    const double s = horizon > 0 ? t / horizon * last : 0.0;
    while (r + 2 < rows && traj.data[(r + 1) * cols] < s) ++r;
    if (rows == 1) return traj.data[c];
    const double t0 = traj.data[r * cols], t1 = traj.data[(r + 1) * cols];
    const double w = t1 > t0 ? std::clamp((s - t0) / (t1 - t0), 0.0, 1.0) : 0.0;
    return (1 - w) * traj.data[r * cols + c] + w * traj.data[(r + 1) * cols + c];
  };
  FileGuess out;
  if (with_controls) out.controls.emplace();
  for (double t : times) {  // increasing: `r` only moves forward
    std::vector<double> x;
    for (size_t c : state_columns) x.push_back(at(t, c));
    out.states.push_back(std::move(x));
    if (!with_controls) continue;
    std::vector<double> u;
    for (size_t c : control_columns) u.push_back(at(t, c));
    out.controls->push_back(std::move(u));
  }
  return out;
}

}  // namespace lagrange::collocation
