// `lagrange trim MODEL [--free NAME,…] [--fix NAME,…] [--steady NAME_dot,…] [--at …] [--tol TOL]`
// (README.md, "Linearise and trim"): an equilibrium or steady state from the model's initial
// state, printed as the model file's initial values.

#include <fmt/format.h>

#include <algorithm>

#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "cli/trim_setup.hpp"
#include "lagrange/analysis.hpp"

namespace lagrange::cli {

namespace {

/// A coordinate an element made (a tether's node `line.node1.x`, a winch's length, a joint of
/// `links:` or a URDF): the file sets its start in the `initial:` section, not in coordinates:.
bool generated(const Model& model, const std::string& name) {
  if (name.find('.') != std::string::npos) return true;
  const int i = model.coordinate_index(name);
  return std::any_of(model.tree.begin(), model.tree.end(),
                     [i](const TreeJoint& j) { return i >= 0 && j.coordinate == i; });
}

// The state found as the model file writes a start: coordinates: for those written there, an
// `initial:` section for generated ones, and every plain one as --initial would take it.
std::string yaml_block(const Model& model, const CompiledModel& cm, const std::vector<double>& q,
                       const std::vector<double>& v) {
  std::string written, made, option;
  for (size_t i = 0; i < cm.plain; ++i) {
    const std::string& name = cm.coordinate_names[i];
    if (generated(model, name))
      made += fmt::format("  {}: {:.17g}\n  {}_dot: {:.17g}\n", name, q[i] + 0.0, name, v[i] + 0.0);
    else
      written +=
          fmt::format("  {}: {{initial: {:.17g}, rate: {:.17g}}}\n", name, q[i] + 0.0, v[i] + 0.0);
    option += fmt::format("{}{}={:.17g},{}_dot={:.17g}", option.empty() ? "" : ",", name,
                          q[i] + 0.0, name, v[i] + 0.0);
  }
  std::string out = "# as --initial: " + option + "\n";
  if (!written.empty()) out += "coordinates:\n" + written;
  if (!made.empty())
    out += "initial:  # coordinates the model's elements generate (tether nodes, joints)\n" + made;
  if (cm.rotations.empty()) return out;
  out += "bodies:  # the free bodies' initial state (merge into each body's entry)\n";
  for (size_t iR : cm.rotations) {
    const std::string& r11 = cm.coordinate_names[iR];
    out += fmt::format("  {}:\n    initial:\n", r11.substr(0, r11.size() - 4));
    out += fmt::format("      position: [{:.17g}, {:.17g}, {:.17g}]\n", q[iR - 3] + 0.0,
                       q[iR - 2] + 0.0, q[iR - 1] + 0.0);
    out += "      orientation: {matrix: [";
    for (size_t i = 0; i < 3; ++i)
      out += fmt::format("{}[{:.17g}, {:.17g}, {:.17g}]", i ? ", " : "", q[iR + 3 * i] + 0.0,
                         q[iR + 3 * i + 1] + 0.0, q[iR + 3 * i + 2] + 0.0);
    out += "]}\n      velocity: [0, 0, 0]\n      omega: [0, 0, 0]\n";
  }
  return out;
}

}  // namespace

int run_trim(const Options& opt) {
  Prepared p = prepare(opt.model, opt.sets, opt.initial, "--at", "lagrangian");
  const CompiledModel& cm = *p.compiled;
  const std::vector<std::string> inputs = trim_inputs(cm, opt);
  const TrimOptions options = trim_options(cm, p.q, p.v, opt, inputs);
  const DynamicsJacobian jac(p.equations, p.compiled, inputs);
  const TrimResult r = trim_prepared(p, jac, options);
  fmt::print("# {}: {}\n", p.model->name, trim_summary(r, !opt.steady.empty(), opt.tol));
  if (cm.m > 0) {
    std::vector<double> C(cm.m), Cdot(cm.m);
    p.dynamics->constraints(0.0, r.q.data(), r.v.data(), C.data(), Cdot.data());
    double worst = 0.0;
    for (double c : C) worst = std::max(worst, std::abs(c));
    fmt::print("# on the constraints: max |C| = {:.3g}\n", worst);
  }
  fmt::print("{}", yaml_block(*p.model, cm, r.q, r.v));
  // The free inputs found, as the model file's parameters (or inputs) would give them.
  for (const bool parameters : {true, false}) {
    std::string block;
    for (size_t k = 0, j = 0; j < inputs.size(); ++j) {
      if (!options.free_inputs[j]) continue;
      const bool parameter =
          std::count(cm.parameter_names.begin(), cm.parameter_names.end(), inputs[j]) > 0;
      if (parameter == parameters)
        block += fmt::format("  {}: {:.17g}\n", inputs[j], r.inputs[k] + 0.0);
      ++k;
    }
    if (!block.empty())
      fmt::print("{}:  # found by trim\n{}", parameters ? "parameters" : "inputs", block);
  }
  return 0;
}

}  // namespace lagrange::cli
