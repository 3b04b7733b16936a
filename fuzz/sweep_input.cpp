#include "sweep_input.hpp"

#include <optional>
#include <vector>

#include "lagrange/simulation.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::fuzz {

namespace {

constexpr size_t kMaxGridValues = 1000;  // cases expanded per input, to keep each run short

Trajectory pendulum_samples() {
  Trajectory traj;
  traj.columns = {"t", "theta", "theta_dot", "kinetic", "potential", "energy", "bob.x"};
  traj.data = {0.0, 1.0,  0.0,  0.0, -5.3, -5.3, 0.84,    // t = 0
               0.5, 0.2,  -2.9, 4.2, -9.5, -5.3, 0.19,    // t = 0.5
               1.0, -0.9, -0.8, 0.3, -5.6, -5.3, -0.78};  // t = 1
  return traj;
}

}  // namespace

std::string parse_sweep_spec(const std::string& text) {
  std::optional<sweep::Axis> axis;
  std::optional<sweep::RandomParameter> random;
  std::string why;
  try {
    axis = sweep::parse_axis(text);
  } catch (const sweep::StudyError& e) {
    why = e.what();
  }
  try {
    random = sweep::parse_random(text);
  } catch (const sweep::StudyError& e) {
    if (!axis) why += std::string(why.empty() ? "" : "; ") + e.what();
  }
  if (!axis && !random) return why;
  std::vector<sweep::Axis> axes;
  if (axis && axis->values.size() <= kMaxGridValues) axes.push_back(*axis);
  std::vector<sweep::RandomParameter> draws;
  if (random) {
    random->name += "_drawn";  // never the grid's name, which make_cases refuses
    draws.push_back(*random);
  }
  if (axes.empty() && draws.empty()) return "ok";
  try {
    (void)sweep::make_cases(axes, draws, draws.empty() ? 0 : 3, 1);
  } catch (const sweep::StudyError& e) {
    return e.what();  // a draw that is not a finite number, named
  }
  return "ok";
}

std::string evaluate_metric_spec(const std::string& text) {
  static const Trajectory traj = pendulum_samples();
  static const std::vector<std::string> parameters{"m", "l", "g"};
  try {
    std::vector<sweep::Metric> metrics{sweep::parse_metric(text)};
    sweep::bind_metrics(metrics, traj.columns, parameters);
    (void)sweep::evaluate(metrics.front(), traj, {1.0, 1.0, 9.81});
  } catch (const sweep::StudyError& e) {
    return e.what();
  }
  return "ok";
}

}  // namespace lagrange::fuzz
