#include "cli/trim_setup.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace lagrange::cli {

namespace {

std::string listed(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s.empty() ? "none" : s;
}

long index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<long>(it - names.begin());
}

bool is_input(const CompiledModel& cm, const std::string& name) {
  return index_of(cm.parameter_names, name) >= 0 || index_of(cm.input_names, name) >= 0;
}

}  // namespace

std::vector<std::string> trim_inputs(const CompiledModel& cm, const Options& opt) {
  std::vector<std::string> names;
  for (const auto& name : opt.free)
    if (is_input(cm, name) && index_of(cm.coordinate_names, name) < 0 && index_of(names, name) < 0)
      names.push_back(name);
  return names;
}

TrimOptions trim_options(const CompiledModel& cm, const std::vector<double>& q,
                         const std::vector<double>& v, const Options& opt,
                         const std::vector<std::string>& inputs) {
  if (!(opt.tol > 0 && std::isfinite(opt.tol)))
    throw UsageError(fmt::format("--tol must be positive and finite, got {}", opt.tol));
  const TangentChart chart = tangent_chart(cm, q.data(), v.data());
  const std::vector<std::string> plain_rates(cm.velocity_names.begin(),
                                             cm.velocity_names.begin() + cm.plain);
  TrimOptions options;
  options.tol = opt.tol;
  options.steady.assign(cm.nv, false);
  options.free_rates.assign(cm.nv, false);
  options.free_inputs.assign(inputs.size(), false);
  for (const auto& name : opt.steady) {
    const long i = index_of(plain_rates, name);
    if (i < 0)
      throw UsageError(fmt::format(
          "--steady: no rate '{}' of a coordinate in the model (expected one of: {}; a free "
          "body's velocities cannot be held, docs/theory.md §5.5)",
          name, listed(plain_rates)));
    options.steady[static_cast<size_t>(i)] = true;
  }
  // The positions: every one that does not move at a held rate unless --free names some.
  options.free.assign(cm.nv, true);
  for (size_t i = 0; i < cm.plain; ++i) options.free[i] = !options.steady[i];
  if (!opt.free.empty()) options.free.assign(cm.nv, false);
  const auto apply = [&](const std::string& option, const std::string& name, bool value) {
    const long x = index_of(chart.names, name);
    if (x >= 0) {
      options.free[static_cast<size_t>(x)] = value;
      return;
    }
    const long r = index_of(plain_rates, name);
    if (r >= 0 && options.steady[static_cast<size_t>(r)]) {
      options.free_rates[static_cast<size_t>(r)] = value;
      return;
    }
    const long w = index_of(inputs, name);
    if (w >= 0) {
      options.free_inputs[static_cast<size_t>(w)] = value;
      return;
    }
    if (is_input(cm, name))
      throw UsageError(
          fmt::format("{}: '{}' is an input or parameter: only --free varies one (with `linearize "
                      "--at-trim`, name it in --inputs too)",
                      option, name));
    throw UsageError(fmt::format(
        "{}: no coordinate '{}' in the model{} (expected a coordinate: {}; a rate held by "
        "--steady; or, for --free, a parameter or input)",
        option, name, r >= 0 ? fmt::format(", and '{}' is not held by --steady", name) : "",
        listed(chart.names)));
  };
  for (const auto& name : opt.free) apply("--free", name, true);
  for (const auto& name : opt.fix) apply("--fix", name, false);
  const auto none = [](const std::vector<bool>& flags) {
    return std::none_of(flags.begin(), flags.end(), [](bool f) { return f; });
  };
  if (none(options.free) && none(options.free_rates) && none(options.free_inputs))
    throw UsageError("--free/--fix leave no coordinate for trim to vary");
  return options;
}

TrimResult trim_prepared(Prepared& p, const DynamicsJacobian& jac, const TrimOptions& options) {
  TrimResult r = trim(jac, *p.dynamics, 0.0, p.q, p.v, options);
  p.q = r.q;
  p.v = r.v;
  return r;
}

std::string trim_summary(const TrimResult& r, bool steady, double tol) {
  std::string s = fmt::format(
      "{} found by {} in {} {}{}, max |acceleration| = {:.3g} (tolerance {:.3g}){}",
      steady ? "steady state" : "equilibrium",
      r.pseudo_transient ? "pseudo-transient continuation (Levenberg–Marquardt alone failed)"
                         : "Levenberg–Marquardt",
      r.iterations, r.pseudo_transient ? "step" : "iteration", r.iterations == 1 ? "" : "s",
      r.residual, r.tolerance, r.not_isolated.empty() ? "" : "; " + r.not_isolated);
  if (!steady) return s;
  return s + fmt::format("; {} along the motion: max |da/dt| = {:.3g}",
                         r.drift <= tol ? "steady" : "only quasi-steady, the accelerations change",
                         r.drift);
}

}  // namespace lagrange::cli
