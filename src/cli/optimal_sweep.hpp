#pragma once
// A study whose cases are optimisations (`lagrange sweep --optimize`, docs/sweeps.md "Optimal
// control"): the model's optimal_control problem solved at every case's values, each case
// started from the solution of the nearest case solved before it, as a power curve is made
// over the wind speed. For the command and the Python module alike.

#include <atomic>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cli/prepare.hpp"
#include "lagrange/optimize.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::cli {

/// The summary's columns of an optimisation study after the case number and the parameters and
/// before the metrics, then after them (docs/sweeps.md, "Optimal control").
extern const std::vector<std::string> kOptimalColumns, kOptimalTrailingColumns;

/// The order in which an optimisation study solves the cases `pending` (indices into `cases`),
/// and for each the case it starts from (docs/sweeps.md, "Optimal control"): distances are
/// measured in each varied parameter divided by its span over the study. The first case is the
/// one nearest `origin` (the model file's own values of the varied parameters, which its
/// first guess is made for), or, when some cases were attempted before (`attempted`: a study
/// resumed), the pending case nearest one of them; then, each time, the pending case nearest a
/// case already attempted (ties: the lower case number). Along one parameter the cases run
/// outwards from the model's own value, each beside one already run.
std::vector<size_t> warm_start_order(const std::vector<sweep::Case>& cases,
                                     const std::vector<size_t>& pending,
                                     const std::vector<double>& origin,
                                     const std::vector<size_t>& attempted = {});

/// The case of `solved` nearest case `index` (same measure), or none when `solved` is empty.
std::optional<size_t> nearest_case(const std::vector<sweep::Case>& cases, size_t index,
                                   const std::vector<size_t>& solved);

/// How one case's optimisation ended.
struct OptimalCaseResult {
  size_t index = 0;
  bool optimal = false;
  std::string reason;  ///< Ipopt's status when not optimal, or why the case could not be solved
  double objective = 0.0, horizon = 0.0, violation = 0.0;  ///< NaN when nothing was solved
  int iterations = 0;
  std::optional<size_t> started_from;  ///< the solved case whose solution started it
  /// When the start from the nearest solution did not converge and the case was solved again
  /// from the problem's own guess: "from case K: Ipopt's status" (`started_from` is then none,
  /// `iterations` and `solve_seconds` count both solves).
  std::string retry;
  /// When a neighbour's solution, tried after both were solved, led to a better optimum: "from
  /// case J's solution (objective before: …)" (`started_from` is then J; docs/sweeps.md,
  /// "Optimal control").
  std::string improved;
  std::vector<double> metrics;  ///< over the result's trajectory (also when not optimal)
  double solve_seconds = 0.0, wall_seconds = 0.0;
};

/// What every case of an optimisation study shares.
struct OptimalStudy {
  const Prepared* prepared = nullptr;  ///< the model derived and compiled once
  OptimizeOptions options;             ///< --intervals, --degree, --ipopt
  /// Metrics bound to optimal_trajectory_columns(); evaluated at the trajectory's samples
  /// (t = 0 and the collocation points).
  std::vector<sweep::Metric> metrics;
  /// Where a warm start's guess is written (a trajectory CSV read back as `guess:`).
  std::string guess_path;
};

/// The columns of optimize()'s trajectory for `p`: simulate's, the controls, the multipliers.
std::vector<std::string> optimal_trajectory_columns(const Prepared& p);

/// The summary's `reason` of a case: Ipopt's status when not optimal, a retry from the problem's
/// guess, a better optimum from a neighbour's solution.
std::string reason_text(const OptimalCaseResult& r);

/// Per case, its neighbours in the study: the cases with the same values but in one parameter,
/// and in that one the next distinct value below or above (a grid's adjacent cases).
std::vector<std::vector<size_t>> grid_neighbours(const std::vector<sweep::Case>& cases);

/// Solves the cases in `order` one after another on `dyn` (a workspace over the study's
/// compiled model), each from its inputs (`read`) and started from the solution of the nearest
/// case in `solved` (index → optimal trajectory; each optimal result is added to it), or, when
/// none is solved yet or that start does not converge, from the problem's own first guess. `done`
/// receives each result and its trajectory (empty when nothing was solved); a case that fails is
/// recorded as such and the study goes on. Then each case is solved again from each optimal grid
/// neighbour's solution it has not started from in that form, and a better optimum found so
/// (local optima: docs/sweeps.md, "Optimal control") goes to `done` again, `improved` set, until
/// no case improves. Stops before the next solve when `interrupt` is set.
void run_optimal_cases(const OptimalStudy& study, Dynamics& dyn,
                       const std::vector<sweep::Case>& cases, const std::vector<size_t>& order,
                       const std::function<sweep::CaseRead(size_t)>& read,
                       std::map<size_t, Trajectory>& solved,
                       const std::function<void(const OptimalCaseResult&, const Trajectory&)>& done,
                       const std::atomic<bool>* interrupt = nullptr);

}  // namespace lagrange::cli
