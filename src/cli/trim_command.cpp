// `lagrange trim MODEL [--free NAME,…] [--fix NAME,…] [--at …] [--tol TOL]` (README.md,
// "Linearise and trim"): an equilibrium from the model's initial state, printed as the
// model file's initial values.

#include <fmt/format.h>

#include <algorithm>

#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "lagrange/analysis.hpp"

namespace lagrange::cli {

namespace {

// Per tangent coordinate: varied by Newton. --free names the varied ones (default all),
// --fix removes names from them.
std::vector<bool> free_flags(const TangentChart& chart, const Options& opt) {
  const auto check = [&](const std::string& option, const std::string& name) {
    const auto it = std::find(chart.names.begin(), chart.names.end(), name);
    if (it == chart.names.end()) {
      std::string known;
      for (const auto& s : chart.names) known += (known.empty() ? "" : ", ") + s;
      throw UsageError(fmt::format("{}: no coordinate '{}' in the model (expected one of: {})",
                                   option, name, known));
    }
    return static_cast<size_t>(it - chart.names.begin());
  };
  std::vector<bool> free(chart.names.size(), opt.free.empty());
  for (const auto& name : opt.free) free[check("--free", name)] = true;
  for (const auto& name : opt.fix) free[check("--fix", name)] = false;
  if (std::none_of(free.begin(), free.end(), [](bool f) { return f; }))
    throw UsageError("--free/--fix leave no coordinate for trim to vary");
  return free;
}

std::string yaml_block(const CompiledModel& cm, const std::vector<double>& q) {
  std::string out = "coordinates:\n";
  for (size_t i = 0; i < cm.plain; ++i)
    out += fmt::format("  {}: {{initial: {:.17g}, rate: 0}}\n", cm.coordinate_names[i], q[i] + 0.0);
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
  if (!(opt.tol > 0)) throw UsageError(fmt::format("--tol must be positive, got {}", opt.tol));
  Prepared p = prepare(opt.model, opt.sets, opt.initial, "--at", "lagrangian");
  const CompiledModel& cm = *p.compiled;
  const DynamicsJacobian jac(p.equations, p.compiled);
  TrimOptions options;
  options.free = free_flags(tangent_chart(cm, p.q.data(), p.v.data()), opt);
  options.tol = opt.tol;
  const TrimResult r = trim(jac, *p.dynamics, 0.0, p.q, options);
  fmt::print(
      "# {}: equilibrium found by Newton's method in {} iteration{}, max |acceleration| = "
      "{:.3g}\n",
      p.model->name, r.iterations, r.iterations == 1 ? "" : "s", r.residual);
  if (cm.m > 0) {
    std::vector<double> C(cm.m), Cdot(cm.m);
    p.dynamics->constraints(0.0, r.q.data(), r.v.data(), C.data(), Cdot.data());
    double worst = 0.0;
    for (double c : C) worst = std::max(worst, std::abs(c));
    fmt::print("# on the constraints: max |C| = {:.3g}\n", worst);
  }
  fmt::print("{}", yaml_block(cm, r.q));
  return 0;
}

}  // namespace lagrange::cli
