// Metrics of a case's trajectory: max, min, mean, final, initial and drift of an expression of
// the columns and the parameters, optionally over a time window (docs/theory.md §9.2).

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "dynamics/row_expression.hpp"
#include "lagrange/error.hpp"
#include "lagrange/sweep.hpp"
#include "model/expression_parser.hpp"
#include "sweep/spec_text.hpp"

namespace lagrange::sweep {

namespace {

const char* kForm =
    "AGG(EXPR) or AGG(EXPR, t > T), EXPR of the trajectory's columns and the parameters, with "
    "AGG one of max, min, mean, final, initial, drift";

// `t > 60`, `t >= 5 and t < 10`: the bounds of the window, into `m`.
void parse_window(const std::string& text, const std::string& context, Metric& m) {
  std::string rest = text;
  for (size_t and_at; !rest.empty();) {
    and_at = rest.find(" and ");
    const std::string cond = trim(rest.substr(0, and_at));
    rest = and_at == std::string::npos ? "" : rest.substr(and_at + 5);
    if (cond.size() < 3 || cond[0] != 't' || (cond[1] != ' ' && cond[1] != '<' && cond[1] != '>'))
      throw StudyError(fmt::format(
          "{}: expected a time window such as 't > 60' or 't >= 5 and t < 10', got '{}'", context,
          cond));
    const std::string op_and_value = trim(cond.substr(1));
    const bool inclusive = op_and_value.size() > 1 && op_and_value[1] == '=';
    const char op = op_and_value[0];
    if (op != '<' && op != '>')
      throw StudyError(
          fmt::format("{}: expected t > T, t >= T, t < T or t <= T, got '{}'", context, cond));
    const double value =
        finite_number(trim(op_and_value.substr(inclusive ? 2 : 1)), context + " (time window)");
    if (op == '>') {
      m.after = value;
      m.after_inclusive = inclusive;
    } else {
      m.before = value;
      m.before_inclusive = inclusive;
    }
  }
}

bool in_window(const Metric& m, double t) {
  if (m.after && !(m.after_inclusive ? t >= *m.after : t > *m.after)) return false;
  if (m.before && !(m.before_inclusive ? t <= *m.before : t < *m.before)) return false;
  return true;
}

/// The summary's columns besides the parameters and the metrics (src/cli/sweep_command.cpp, the
/// Python study's frame).
const std::array<std::string, 5> kSummaryColumns{"case", "status", "reason", "failure_time",
                                                 "wall_s"};

}  // namespace

Metric parse_metric(const std::string& spec, const std::string& where) {
  Metric m;
  const std::string context = where.empty() ? fmt::format("--metric {}", spec) : where;
  std::string expr = trim(spec);
  const auto open = expr.find('(');
  if (const auto eq = expr.find('='); eq != std::string::npos && eq < open) {
    m.name = trim(expr.substr(0, eq));
    expr = trim(expr.substr(eq + 1));
  }
  m.text = expr;
  if (m.name.empty()) m.name = expr;
  const auto paren = expr.find('(');
  if (paren == std::string::npos || expr.back() != ')')
    throw StudyError(fmt::format("{}: expected {}", context, kForm));
  const std::string agg = trim(expr.substr(0, paren));
  if (agg == "max") {
    m.aggregate = Metric::Aggregate::Max;
  } else if (agg == "min") {
    m.aggregate = Metric::Aggregate::Min;
  } else if (agg == "mean") {
    m.aggregate = Metric::Aggregate::Mean;
  } else if (agg == "final") {
    m.aggregate = Metric::Aggregate::Final;
  } else if (agg == "initial") {
    m.aggregate = Metric::Aggregate::Initial;
  } else if (agg == "drift") {
    m.aggregate = Metric::Aggregate::Drift;
  } else {
    throw StudyError(fmt::format("{}: unknown aggregate '{}'; expected {}", context, agg, kForm));
  }
  // The argument and the optional window, split at the first comma outside parentheses.
  const std::string inner = expr.substr(paren + 1, expr.size() - paren - 2);
  int depth = 0;
  size_t comma = std::string::npos;
  for (size_t i = 0; i < inner.size() && comma == std::string::npos; ++i) {
    if (inner[i] == '(') ++depth;
    if (inner[i] == ')') --depth;
    if (inner[i] == ',' && depth == 0) comma = i;
  }
  m.expression = trim(inner.substr(0, comma));
  if (comma != std::string::npos) parse_window(trim(inner.substr(comma + 1)), context, m);
  if (m.expression.empty())
    throw StudyError(fmt::format("{}: expected {}, got nothing to aggregate", context, kForm));
  return m;
}

void bind_metrics(std::vector<Metric>& metrics, const std::vector<std::string>& columns,
                  const std::vector<std::string>& parameters) {
  const RowSymbols names(columns, parameters);
  for (Metric& m : metrics) {
    GiNaC::ex e;
    try {
      e = names.parse(m.expression);
    } catch (const model::ExprError& err) {
      std::string known;
      for (const auto& c : columns) known += (known.empty() ? "" : ", ") + c;
      throw StudyError(
          fmt::format("metric '{}': {} in '{}' (the names are the trajectory's "
                      "columns and the parameters; columns: {})",
                      m.name, err.message, m.expression, known));
    }
    m.tape = std::make_shared<const Tape>(Tape::compile({e}, names.inputs()));
    m.columns = columns.size();
  }
}

std::vector<Metric> study_metrics(const Model& model, const CompiledModel& cm,
                                  const std::vector<std::string>& specs,
                                  const std::vector<std::string>& bound_to) {
  std::vector<Metric> metrics;
  std::vector<SourceLoc> where;  // of the model file's metrics
  for (const MetricSpec& spec : model.metrics) {
    try {
      metrics.push_back(parse_metric(spec.name + "=" + spec.text, "metric " + spec.name));
    } catch (const StudyError& e) {
      throw ModelError(spec.loc, e.what());
    }
    where.push_back(spec.loc);
  }
  for (const std::string& s : specs) metrics.push_back(parse_metric(s));
  for (size_t i = 0; i < metrics.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (metrics[i].name == metrics[j].name)
        throw StudyError(
            fmt::format("metric '{}' is given twice{}", metrics[i].name,
                        j < where.size() ? " (in the model file and by --metric)" : ""));
  // A metric is a column of the summary beside the case number, the parameters and the status
  // columns: one named like them would shadow that column (issue 37 item 7).
  for (size_t i = 0; i < metrics.size(); ++i) {
    const std::string& name = metrics[i].name;
    std::string clash;
    if (std::count(kSummaryColumns.begin(), kSummaryColumns.end(), name))
      clash = "a column every summary has (case, status, reason, failure_time, wall_s)";
    else if (std::count(cm.parameter_names.begin(), cm.parameter_names.end(), name))
      clash = "a parameter, whose column in the summary it would shadow";
    if (clash.empty()) continue;
    const std::string what =
        fmt::format("metric '{}' is named like {}; give it another name", name, clash);
    if (i < where.size()) throw ModelError(where[i], what);
    throw StudyError(what);
  }
  const std::vector<std::string> columns = bound_to.empty() ? trajectory_columns(cm) : bound_to;
  for (size_t i = 0; i < metrics.size(); ++i) {
    std::vector<Metric> one{metrics[i]};
    try {
      bind_metrics(one, columns, cm.parameter_names);
    } catch (const StudyError& e) {
      if (i < where.size()) throw ModelError(where[i], e.what());
      throw;
    }
    metrics[i] = std::move(one.front());
  }
  return metrics;
}

namespace {

/// The metric's value on one row of `nc` columns, with the parameters already in `in`.
double metric_at(const Metric& metric, const double* row, size_t nc, std::vector<double>& in,
                 std::vector<double>& work) {
  std::copy_n(row, nc, in.begin());
  double x = 0.0;
  metric.tape->eval(in.data(), &x, work.data());
  return x;
}

}  // namespace

namespace {

// docs/theory.md §9.2: the aggregate over the samples in the window, in time order; `best` the
// row where max or min is reached.
double aggregate(const Metric& metric, const Trajectory& traj,
                 const std::vector<double>& parameters, size_t& best) {
  const size_t nc = traj.columns.size(), tcol = traj.column_index("t");
  if (!metric.tape || metric.columns != nc || metric.tape->num_inputs() != nc + parameters.size())
    throw std::logic_error(fmt::format(
        "metric {}: bound to {} columns and {} parameters, evaluated on {} and {}", metric.text,
        metric.columns, metric.tape ? metric.tape->num_inputs() - metric.columns : 0, nc,
        parameters.size()));
  std::vector<double> in(nc + parameters.size()), work(metric.tape->work_size());
  std::copy(parameters.begin(), parameters.end(), in.begin() + static_cast<long>(nc));
  double result = std::numeric_limits<double>::quiet_NaN(), sum = 0.0, first = 0.0;
  size_t count = 0;
  for (size_t r = 0; r < traj.rows(); ++r) {
    if (!in_window(metric, traj.data[r * nc + tcol])) continue;
    const double x = metric_at(metric, traj.data.data() + r * nc, nc, in, work);
    switch (metric.aggregate) {
      case Metric::Aggregate::Max:
        if (count == 0 || x > result) result = x, best = r;
        break;
      case Metric::Aggregate::Min:
        if (count == 0 || x < result) result = x, best = r;
        break;
      case Metric::Aggregate::Mean:
        sum += x;
        break;
      case Metric::Aggregate::Final:
        result = x;
        break;
      case Metric::Aggregate::Initial:
        if (count == 0) result = x;
        break;
      case Metric::Aggregate::Drift:
        if (count == 0) first = x;
        result = count == 0 ? 0.0 : std::max(result, std::abs(x - first));
        break;
    }
    ++count;
  }
  if (metric.aggregate == Metric::Aggregate::Mean && count > 0)
    result = sum / static_cast<double>(count);
  return result;
}

}  // namespace

double evaluate(const Metric& metric, const Trajectory& traj,
                const std::vector<double>& parameters) {
  size_t best = 0;
  return aggregate(metric, traj, parameters, best);
}

// docs/theory.md §9.2: max and min between samples. The extremum the samples show at row r
// lies in [t(r−1), t(r+1)], cut to the window and the run; golden-section search there on the
// metric of rows integrated from the sample before finds it to 1e-10 (1 + |t|) in time (at a
// window's edge, the value there).
double evaluate(const Metric& metric, const Trajectory& traj, const std::vector<double>& parameters,
                const RowAt& row_at) {
  size_t r = 0;
  const double sampled = aggregate(metric, traj, parameters, r);
  const bool max = metric.aggregate == Metric::Aggregate::Max;
  if ((!max && metric.aggregate != Metric::Aggregate::Min) || std::isnan(sampled)) return sampled;
  const size_t nc = traj.columns.size(), tcol = traj.column_index("t");
  const auto t_of = [&](size_t row) { return traj.data[row * nc + tcol]; };
  const size_t from = r > 0 ? r - 1 : r;
  double a = t_of(from), b = t_of(r + 1 < traj.rows() ? r + 1 : r);
  if (metric.after) a = std::max(a, *metric.after);
  if (metric.before) b = std::min(b, *metric.before);
  if (!(b > a)) return sampled;
  std::vector<double> in(nc + parameters.size()), work(metric.tape->work_size());
  std::copy(parameters.begin(), parameters.end(), in.begin() + static_cast<long>(nc));
  // The value to maximise: the metric, or minus it for min.
  const auto f = [&](double t) {
    const std::vector<double> row = row_at(from, t);
    const double x = metric_at(metric, row.data(), nc, in, work);
    return max ? x : -x;
  };
  const double g = (std::sqrt(5.0) - 1) / 2;  // 1/φ
  double c = b - g * (b - a), d = a + g * (b - a), fc = f(c), fd = f(d);
  for (int it = 0; it < 200 && b - a > 1e-10 * (1 + std::abs(b)); ++it) {
    if (fc >= fd) {
      b = d, d = c, fd = fc;
      c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd;
      d = a + g * (b - a), fd = f(d);
    }
  }
  const double found = std::max(fc, fd);
  if (!std::isfinite(found)) return sampled;
  return max ? std::max(sampled, found) : std::min(sampled, -found);
}

RowAt rows_between_samples(Dynamics& dyn, const SimulationOptions& options,
                           const Trajectory& traj) {
  const CompiledModel& cm = dyn.model();
  const size_t nc = traj.columns.size(), tcol = traj.column_index("t");
  std::vector<size_t> qcol, vcol;
  for (const auto& name : cm.coordinate_names) qcol.push_back(traj.column_index(name));
  for (const auto& name : cm.velocity_names) vcol.push_back(traj.column_index(name));
  return [&dyn, options, &traj, nc, tcol, qcol, vcol](size_t row, double t) {
    const double* sample = traj.data.data() + row * nc;
    if (!(t > sample[tcol])) return std::vector<double>(sample, sample + nc);
    std::vector<double> q, v;
    for (size_t i : qcol) q.push_back(sample[i]);
    for (size_t i : vcol) v.push_back(sample[i]);
    SimulationOptions one = options;
    one.progress = nullptr;  // a piece of the run already reported
    one.t0 = sample[tcol];
    one.t_end = t;
    one.output_step = t - one.t0;
    const Trajectory piece = simulate(dyn, one, q, v);
    if (piece.rows() == 0) return std::vector<double>(nc, std::nan(""));
    return std::vector<double>(piece.data.end() - static_cast<long>(nc), piece.data.end());
  };
}

}  // namespace lagrange::sweep
