#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lagrange/integrator.hpp"
#include "model/model_reader.hpp"

namespace lagrange::model {

void ModelReader::read_stabilization(const YAML::Node& node) {
  check_keys(node, {"alpha", "project", "gamma"}, "stabilization");
  Stabilization& s = m_.stabilization;
  s.loc = src_.at(node);
  if (node["alpha"]) {
    const double alpha = number(node["alpha"], kParams, "stabilization alpha");
    if (alpha < 0) fail(node["alpha"], fmt::format("expected alpha >= 0, got {:g}", alpha));
    s.alpha = alpha;
  }
  if (node["project"]) s.project = boolean(node["project"], "stabilization project");
  if (node["gamma"]) {
    s.gamma = number(node["gamma"], kParams, "stabilization gamma");
    if (s.gamma < 0) fail(node["gamma"], fmt::format("expected gamma >= 0, got {:g}", s.gamma));
  }
}

void ModelReader::read_simulate(const YAML::Node& node) {
  check_keys(node, {"t_end", "output_step", "integrator", "rtol", "atol", "step", "max_order"},
             "simulate");
  SimulateOptions& o = m_.simulate;
  o.loc = src_.at(node);
  auto positive = [&](const char* key, double& out, bool allow_zero) {
    if (!node[key]) return;
    out = number(node[key], kParams, fmt::format("simulate {}", key));
    if (out < 0 || (!allow_zero && out == 0))
      fail(node[key], fmt::format("expected {} {} 0, got {:g}", key, allow_zero ? ">=" : ">", out));
  };
  positive("t_end", o.t_end, false);
  positive("output_step", o.output_step, false);
  positive("rtol", o.rtol, false);
  positive("atol", o.atol, false);
  positive("step", o.step, true);
  if (node["max_order"]) {
    const double order = number(node["max_order"], kParams, "simulate max_order");
    if (order != std::floor(order) || order < 1 || order > 5)
      fail(node["max_order"],
           fmt::format("expected max_order an integer from 1 to 5 (the BDF methods' highest "
                       "order), got {:g}",
                       order));
    o.max_order = static_cast<int>(order);
  }
  if (node["integrator"]) {
    o.integrator = scalar(node["integrator"], "simulate integrator");
    const std::vector<std::string>& known = integrator_methods();
    if (std::find(known.begin(), known.end(), o.integrator) == known.end())
      fail(node["integrator"], fmt::format("unknown integrator '{}', expected one of: {}",
                                           clip(o.integrator), integrator_method_list()));
  }
}

void ModelReader::read_stop_when(const YAML::Node& node) {
  expect_map(node, "stop_when (a map name: condition, e.g. touchdown: kite.z < 0)");
  check_keys(node, {}, "stop_when");
  for (const auto& kv : node) {
    const std::string name = scalar(kv.first, "name of a stop condition");
    const std::string what = fmt::format("stop condition '{}'", name);
    const std::string text = scalar(kv.second, what);
    // A condition fires where its sides cross, located to the time they are equal: lhs <= rhs
    // is the same condition as lhs < rhs, and lhs == rhs is that crossing, in either direction.
    for (const std::string op : {"<=", ">=", "=="})
      if (text.find(op) != std::string::npos)
        fail(kv.second,
             fmt::format("expected only '<' or '>' in {}, got '{}' in '{}': a stop condition "
                         "fires when its sides cross, located to where they are equal, so {}",
                         what, op, clip(text),
                         op == "==" ? "write 'lhs < rhs' or 'lhs > rhs' for the crossing you mean"
                                    : fmt::format("'{}' is the same condition", op.substr(0, 1))));
    size_t comparisons = 0;
    for (char c : text) comparisons += c == '<' || c == '>';
    if (comparisons != 1)
      fail(kv.second, fmt::format("expected one comparison 'lhs < rhs' or 'lhs > rhs' for {}, "
                                  "got {} in '{}'",
                                  what, comparisons == 0 ? "none" : "several", clip(text)));
    m_.stop_when.push_back(StopSpec{name, text, src_.at(kv.second)});
  }
}

void ModelReader::read_metrics(const YAML::Node& node) {
  expect_map(node, "metrics (a map name: aggregate, e.g. peak: max(abs(theta)))");
  check_keys(node, {}, "metrics");
  for (const auto& kv : node) {
    const std::string name = scalar(kv.first, "name of a metric");
    m_.metrics.push_back(
        MetricSpec{name, scalar(kv.second, fmt::format("metric '{}'", name)), src_.at(kv.second)});
  }
}

}  // namespace lagrange::model
