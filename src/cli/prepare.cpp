#include "cli/prepare.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "cli/commands.hpp"
#include "cli/initial_state.hpp"
#include "lagrange/error.hpp"

namespace lagrange::cli {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Prepared prepare_with(const std::string& path, const ParameterOverrides& overrides) {
  Prepared p;
  const auto t0 = Clock::now();
  p.model = std::make_unique<const Model>(read_model_file(path, overrides));
  p.equations = derive(*p.model);
  p.derive_seconds = seconds_since(t0);
  const auto t1 = Clock::now();
  p.compiled = compile(p.equations);
  p.dynamics = std::make_unique<Dynamics>(p.compiled, p.compiled->parameter_defaults);
  p.dynamics->set_baumgarte(p.model->stabilization.alpha);
  p.compile_seconds = seconds_since(t1);
  p.q = p.compiled->q0;
  p.v = p.compiled->v0;
  p.initial = require_consistent_initial_state(*p.model, *p.dynamics, p.q, p.v);
  require_regular_initial_state(*p.model, p.equations, *p.dynamics, p.q, p.v);
  return p;
}

bool prepares_as_written(const std::string& path) {
  try {
    (void)prepare_with(path, {});
    return true;
  } catch (const ModelError&) {
    return false;
  }
}

}  // namespace

ParameterOverrides parse_sets(const std::vector<std::string>& sets) {
  ParameterOverrides out;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq == std::string::npos) throw UsageError("--set expects NAME=VALUE, got '" + s + "'");
    const std::string name = s.substr(0, eq), text = s.substr(eq + 1);
    try {
      size_t used = 0;
      const double value = std::stod(text, &used);
      if (used != text.size() || !std::isfinite(value)) throw std::invalid_argument(s);
      out[name] = value;
    } catch (const std::exception&) {
      throw UsageError("--set: expected a finite number after '" + name + "=', got '" + text + "'");
    }
  }
  return out;
}

Prepared prepare(const std::string& path, const std::vector<std::string>& sets) {
  const ParameterOverrides overrides = parse_sets(sets);
  try {
    return prepare_with(path, overrides);
  } catch (const ParameterOverrideError& e) {
    throw UsageError(fmt::format("--set: {}", e.what()));
  } catch (const ModelError& e) {
    // The file's own mistake stays a model error; a value only the command line brings is its.
    if (overrides.empty() || !prepares_as_written(path)) throw;
    std::string given;
    for (const auto& s : sets) given += (given.empty() ? "--set " : " --set ") + s;
    throw UsageError(fmt::format("{}: the model does not accept this value: {} (found at {})",
                                 given, e.detail(), e.loc().str()));
  }
}

}  // namespace lagrange::cli
