// An optimisation study's cases (cli/optimal_sweep.hpp): the order they are solved in, each
// started from the nearest solution found before it (docs/sweeps.md, "Optimal control").

#include "cli/optimal_sweep.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "lagrange/io.hpp"
#include "support/seconds_since.hpp"

namespace lagrange::cli {

const std::vector<std::string> kOptimalColumns = {"status",     "reason",    "objective", "horizon",
                                                  "iterations", "violation", "warm_start"};
const std::vector<std::string> kOptimalTrailingColumns = {"solve_s", "wall_s"};

namespace {

// Each varied parameter's span over the study (1 where it does not vary), the unit of the
// distance between cases (docs/sweeps.md, "Optimal control").
std::vector<double> spans(const std::vector<sweep::Case>& cases) {
  const size_t k = cases.empty() ? 0 : cases.front().values.size();
  std::vector<double> lo(k, std::numeric_limits<double>::infinity()), hi(k, -lo[0]);
  for (const sweep::Case& c : cases)
    for (size_t i = 0; i < k; ++i) {
      lo[i] = std::min(lo[i], c.values[i].second);
      hi[i] = std::max(hi[i], c.values[i].second);
    }
  std::vector<double> span(k, 1.0);
  for (size_t i = 0; i < k; ++i)
    if (hi[i] > lo[i]) span[i] = hi[i] - lo[i];
  return span;
}

// The squared distance between a case's values and `at`, each divided by its span.
double distance(const sweep::Case& c, const std::vector<double>& at,
                const std::vector<double>& span) {
  double d = 0.0;
  for (size_t i = 0; i < span.size(); ++i) {
    const double x = (c.values[i].second - at[i]) / span[i];
    d += x * x;
  }
  return d;
}

std::vector<double> values_of(const sweep::Case& c) {
  std::vector<double> v;
  for (const auto& [name, value] : c.values) v.push_back(value);
  return v;
}

}  // namespace

std::vector<size_t> warm_start_order(const std::vector<sweep::Case>& cases,
                                     const std::vector<size_t>& pending,
                                     const std::vector<double>& origin,
                                     const std::vector<size_t>& attempted) {
  const std::vector<double> span = spans(cases);
  // nearest[i]: the distance of pending[i] to the nearest case attempted so far (to the origin
  // before any), updated as each case is taken: O(n²) for n cases.
  std::vector<double> nearest(pending.size(), std::numeric_limits<double>::infinity());
  for (size_t i = 0; i < pending.size(); ++i) {
    const sweep::Case& c = cases.at(pending[i]);
    if (attempted.empty()) nearest[i] = distance(c, origin, span);
    for (size_t a : attempted)
      nearest[i] = std::min(nearest[i], distance(c, values_of(cases.at(a)), span));
  }
  std::vector<bool> taken(pending.size(), false);
  std::vector<size_t> order;
  for (size_t n = 0; n < pending.size(); ++n) {
    size_t best = pending.size();
    for (size_t i = 0; i < pending.size(); ++i)
      if (!taken[i] && (best == pending.size() || nearest[i] < nearest[best] ||
                        (nearest[i] == nearest[best] && pending[i] < pending[best])))
        best = i;
    taken[best] = true;
    order.push_back(pending[best]);
    const std::vector<double> at = values_of(cases.at(pending[best]));
    for (size_t i = 0; i < pending.size(); ++i)
      if (!taken[i]) nearest[i] = std::min(nearest[i], distance(cases.at(pending[i]), at, span));
  }
  return order;
}

std::optional<size_t> nearest_case(const std::vector<sweep::Case>& cases, size_t index,
                                   const std::vector<size_t>& solved) {
  const std::vector<double> span = spans(cases), at = values_of(cases.at(index));
  std::optional<size_t> best;
  double d_best = std::numeric_limits<double>::infinity();
  for (size_t s : solved) {
    const double d = distance(cases.at(s), at, span);
    if (!best || d < d_best || (d == d_best && s < *best)) {
      best = s;
      d_best = d;
    }
  }
  return best;
}

std::vector<std::string> optimal_trajectory_columns(const Prepared& p) {
  std::vector<std::string> columns = trajectory_columns(*p.compiled);
  for (const ControlSpec& c : p.model->optimal_control->controls)
    columns.push_back(p.model->inputs.at(c.input).name);
  for (const std::string& n : p.compiled->constraint_names) columns.push_back("lambda_" + n);
  return columns;
}

std::string reason_text(const OptimalCaseResult& r) {
  std::string text = r.reason;
  const auto add = [&](const std::string& part) { text += (text.empty() ? "" : "; ") + part; };
  if (!r.retry.empty())
    add(fmt::format("started {}; solved again from the problem's guess", r.retry));
  if (!r.improved.empty()) add("improved " + r.improved);
  return text;
}

std::vector<std::vector<size_t>> grid_neighbours(const std::vector<sweep::Case>& cases) {
  std::vector<std::vector<size_t>> out(cases.size());
  const size_t k = cases.empty() ? 0 : cases.front().values.size();
  for (size_t i = 0; i < cases.size(); ++i)
    for (size_t d = 0; d < k; ++d) {
      // The nearest case below and above in parameter d among those equal in the others.
      std::optional<size_t> below, above;
      const double at = cases[i].values[d].second;
      for (size_t j = 0; j < cases.size(); ++j) {
        bool same = j != i;
        for (size_t e = 0; e < k && same; ++e)
          if (e != d) same = cases[j].values[e].second == cases[i].values[e].second;
        if (!same) continue;
        const double v = cases[j].values[d].second;
        if (v < at && (!below || v > cases[*below].values[d].second)) below = j;
        if (v > at && (!above || v < cases[*above].values[d].second)) above = j;
      }
      for (const auto& n : {below, above})
        if (n) out[i].push_back(*n);
    }
  return out;
}

void run_optimal_cases(const OptimalStudy& study, Dynamics& dyn,
                       const std::vector<sweep::Case>& cases, const std::vector<size_t>& order,
                       const std::function<sweep::CaseRead(size_t)>& read,
                       std::map<size_t, Trajectory>& solved,
                       const std::function<void(const OptimalCaseResult&, const Trajectory&)>& done,
                       const std::atomic<bool>* interrupt) {
  const Prepared& p = *study.prepared;
  const double nan = std::nan("");
  const bool maximize = p.model->optimal_control->maximize;
  // Solves case `index` from the solution of case `from` (none: the problem's own guess, its
  // homotopy stages included) into r and traj; false when its inputs cannot be read or made
  // consistent (r.reason says why).
  const auto solve = [&](size_t index, std::optional<size_t> from, OptimalCaseResult& r,
                         Trajectory& traj) {
    try {
      const sweep::CaseRead in = read(index);
      if (!in.input) throw std::runtime_error(in.rejected);
      // The case's parameters and its initial state made consistent, as sweep::run_case does
      // for a simulation (docs/theory.md §4.3); the problem is the model file's.
      dyn.set_parameters(in.input->parameters);
      dyn.set_baumgarte(in.input->baumgarte);
      std::vector<double> q = in.input->q0, v = in.input->v0;
      const InitialConsistency ic =
          make_initial_state_consistent(dyn, 0.0, q, v, SimulationOptions{}.projection_tol);
      if (!ic.consistent)
        throw std::runtime_error(fmt::format(
            "the initial state cannot be made consistent with the constraints (max |C| = "
            "{:.3g}, max |Cdot| = {:.3g} after projection)",
            ic.projection.residual, ic.projection.rate_residual));
      OptimalControlSpec spec = *p.model->optimal_control;
      if (from) {
        // A neighbour's solution is where a homotopy would lead: its stages are left out.
        write_trajectory_csv(solved.at(*from), study.guess_path);
        spec.guess_file = study.guess_path;
        spec.stages.clear();
      }
      OptimizeResult o = optimize(p.equations, p.compiled, dyn, spec, q, v, study.options);
      r.solve_seconds += o.solve_seconds;
      r.iterations += o.iterations;
      r.optimal = o.optimal;
      r.reason = o.optimal ? "" : o.status;
      r.objective = o.objective;
      r.horizon = o.horizon;
      r.violation = o.violation;
      traj = std::move(o.trajectory);
      for (size_t m = 0; m < study.metrics.size(); ++m)
        r.metrics[m] = sweep::evaluate(study.metrics[m], traj, in.input->parameters);
      return true;
    } catch (const std::exception& e) {
      r.optimal = false;
      r.reason = e.what();
      return false;
    }
  };
  const auto fresh = [&](size_t index) {
    OptimalCaseResult r;
    r.index = index;
    r.objective = r.horizon = r.violation = nan;
    r.metrics.assign(study.metrics.size(), nan);
    return r;
  };
  const std::vector<std::vector<size_t>> neighbours = grid_neighbours(cases);
  // version[j] counts the changes of case j's solution; tried[{i, j}]: the version of j's
  // solution case i last started from.
  std::vector<int> version(cases.size(), 0);
  std::map<std::pair<size_t, size_t>, int> tried;
  std::map<size_t, std::pair<OptimalCaseResult, Trajectory>> results;
  for (const size_t index : order) {
    if (interrupt != nullptr && interrupt->load()) return;
    const auto start = std::chrono::steady_clock::now();
    OptimalCaseResult r = fresh(index);
    Trajectory traj;
    std::vector<size_t> converged;
    for (const auto& [i, t] : solved) converged.push_back(i);
    r.started_from = nearest_case(cases, index, converged);
    if (r.started_from) tried[{index, *r.started_from}] = 0;
    if (solve(index, r.started_from, r, traj) && !r.optimal && r.started_from) {
      // A neighbour's solution that leads nowhere: the problem's own guess, as the first case
      // had (docs/sweeps.md, "Optimal control").
      r.retry = fmt::format("from case {}: {}", *r.started_from, r.reason);
      r.started_from.reset();
      solve(index, std::nullopt, r, traj);
    }
    if (r.optimal) solved[index] = traj;
    r.wall_seconds = seconds_since(start);
    done(r, traj);
    results.emplace(index, std::make_pair(std::move(r), std::move(traj)));
  }
  // docs/sweeps.md, "Optimal control": each case again from every optimal neighbour's solution
  // it has not started from in its present form, keeping a better optimum (a failed case: any
  // optimum), until none improves (at most kImprovementPasses passes over the study).
  constexpr int kImprovementPasses = 4;
  for (int pass = 0; pass < kImprovementPasses; ++pass) {
    bool changed = false;
    for (const size_t index : order) {
      auto& [r, traj] = results.at(index);
      for (const size_t j : neighbours[index]) {
        if (interrupt != nullptr && interrupt->load()) return;
        const auto t = tried.find({index, j});
        if (!solved.count(j) || (t != tried.end() && t->second == version[j])) continue;
        tried[{index, j}] = version[j];
        const auto start = std::chrono::steady_clock::now();
        OptimalCaseResult again = fresh(index);
        Trajectory from_j;
        solve(index, j, again, from_j);
        r.iterations += again.iterations;
        r.solve_seconds += again.solve_seconds;
        r.wall_seconds += seconds_since(start);
        const double margin = 1e-6 * (1 + std::fabs(r.objective));
        const bool better = !r.optimal || (maximize ? again.objective > r.objective + margin
                                                    : again.objective < r.objective - margin);
        if (!again.optimal || !better) continue;
        again.improved =
            r.optimal
                ? fmt::format("from case {}'s solution (objective before: {:.10g})", j, r.objective)
                : fmt::format("from case {}'s solution (failed before: {})", j, r.reason);
        again.iterations = r.iterations;
        again.solve_seconds = r.solve_seconds;
        again.wall_seconds = r.wall_seconds;
        again.retry = r.retry;
        again.started_from = j;
        r = std::move(again);
        traj = std::move(from_j);
        solved[index] = traj;
        ++version[index];
        changed = true;
        done(r, traj);
      }
    }
    if (!changed) return;
  }
}

}  // namespace lagrange::cli
