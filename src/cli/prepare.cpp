#include "cli/prepare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "cli/commands.hpp"
#include "cli/initial_state.hpp"
#include "lagrange/error.hpp"
#include "lagrange/io.hpp"
#include "lagrange/reader.hpp"
#include "support/seconds_since.hpp"

namespace lagrange::cli {

namespace {

using Clock = std::chrono::steady_clock;

// `--initial NAME=VALUE`: a coordinate (position) or `NAME_dot` (velocity) of the compiled model.
// A free body's rotation entries are left to the model file: nine numbers that must stay a
// rotation.
void apply_initial(const CompiledModel& cm,
                   const std::vector<std::pair<std::string, double>>& given,
                   const std::string& option, std::vector<double>& q, std::vector<double>& v) {
  for (const auto& [name, value] : given) {
    // (A lambda may not capture a structured binding before C++20: pass the name.)
    const auto in = [](const std::vector<std::string>& names, const std::string& wanted) {
      return std::find(names.begin(), names.end(), wanted) - names.begin();
    };
    const auto iq = static_cast<size_t>(in(cm.coordinate_names, name));
    const auto iv = static_cast<size_t>(in(cm.velocity_names, name));
    const bool rotation =
        iq < cm.nq && std::any_of(cm.rotations.begin(), cm.rotations.end(),
                                  [&](size_t r) { return iq >= r && iq < r + 9; });
    if (rotation)
      throw UsageError(
          fmt::format("{} {}: a body's rotation matrix entry; set the body's "
                      "initial orientation in the model file",
                      option, name));
    if (iq < cm.nq) {
      q[iq] = value;
    } else if (iv < cm.nv) {
      v[iv] = value;
    } else {
      std::string known;
      for (size_t i = 0; i < cm.plain; ++i)
        known += (known.empty() ? "" : ", ") + cm.coordinate_names[i];
      throw UsageError(fmt::format(
          "{}: no coordinate or velocity '{}' in the model (coordinates: {}; velocities are "
          "NAME_dot)",
          option, name, known.empty() ? "none" : known));
    }
  }
}

/// The state given on the command line (`--initial` or `--state`) as NAME and value text, and
/// its option's name.
struct GivenState {
  std::vector<std::pair<std::string, std::string>> values;
  std::string option;
};

/// The model's parameters by name at their values (after --set): what a start value may name.
std::map<std::string, double> parameter_values(const Model& model) {
  std::map<std::string, double> out;
  for (const Parameter& p : model.parameters) out[p.name] = p.value;
  return out;
}

Prepared prepare_with(const ModelSource& source, const ParameterOverrides& overrides,
                      const GivenState& initial, const std::string& dynamics) {
  Prepared p;
  const auto t0 = Clock::now();
  // The start values go to the reader, so that what it builds from them (a tether's nodes)
  // follows; apply_initial sets them again with those it leaves (a free body's position).
  p.model = std::make_unique<const Model>(source.read(overrides, initial.values));
  const Formulation form = formulation(*p.model, dynamics);
  try {
    p.equations = derive(*p.model, form);
  } catch (const GiNaC::pole_error&) {
    // Another exact pole of the articulated-body algorithm than a zero pivot (which derive
    // reports at its coordinate): the Lagrangian form reaches the initial state check below.
    if (form != Formulation::Recursive) throw;
    p.equations = derive(*p.model, Formulation::Lagrangian);
  }
  p.derive_seconds = seconds_since(t0);
  const auto t1 = Clock::now();
  p.compiled = compile(p.equations);
  p.dynamics = std::make_unique<Dynamics>(p.compiled, p.compiled->parameter_defaults);
  p.dynamics->set_baumgarte(baumgarte_rate(p.model->stabilization, p.model->simulate.integrator));
  p.compile_seconds = seconds_since(t1);
  p.q = p.compiled->q0;
  p.v = p.compiled->v0;
  apply_initial(*p.compiled,
                evaluate_assignments(initial.values, initial.option, parameter_values(*p.model)),
                initial.option, p.q, p.v);
  try {
    p.initial = require_consistent_initial_state(*p.model, *p.dynamics, p.q, p.v);
    require_regular_initial_state(*p.model, p.equations, *p.dynamics, p.q, p.v);
  } catch (const ModelError& e) {
    // A state the file's own initial values pass is the command line's mistake (issue 37 item
    // 18): `--at l=0` is not an error at the file's line. The start values reach the reader, so
    // the file's own state is the model prepared again without them (on this error path only).
    bool own_state_passes = false;
    if (!initial.values.empty()) {
      try {
        GivenState none;
        none.option = initial.option;
        (void)prepare_with(source, overrides, none, dynamics);
        own_state_passes = true;
      } catch (const ModelError&) {
      }
    }
    if (!own_state_passes) throw;
    std::string given;
    for (const auto& [name, value] : initial.values)
      given += fmt::format("{}{}={}", given.empty() ? "" : ",", name, value);
    throw UsageError(fmt::format("{} {}: the model does not accept this state: {} (found at {})",
                                 initial.option, given, e.detail(), e.loc().str()));
  }
  return p;
}

bool prepares_as_written(const ModelSource& source, const std::string& dynamics) {
  try {
    (void)prepare_with(source, {}, {}, dynamics);
    return true;
  } catch (const ModelError&) {
    return false;
  }
}

// prepare_with, with the caller's values blamed (as `option`: "--set" or "set", the values
// spelled `given`) for a ModelError that the file as written does not have.
Prepared prepare_checked(const ModelSource& source, const ParameterOverrides& overrides,
                         const GivenState& initial, const std::string& dynamics,
                         const std::string& option, const std::string& given) {
  try {
    return prepare_with(source, overrides, initial, dynamics);
  } catch (const ParameterOverrideError& e) {
    throw UsageError(fmt::format("{}: {}", option, e.what()));
  } catch (const ValueTextError& e) {
    throw UsageError(fmt::format("{}: {}", initial.option, e.what()));
  } catch (const ModelError& e) {
    // The file's own mistake stays a model error; a value only the caller brings is its.
    if (overrides.empty() || !prepares_as_written(source, dynamics)) throw;
    throw UsageError(fmt::format("{}: the model does not accept this value: {} (found at {})",
                                 given, e.detail(), e.loc().str()));
  }
}

}  // namespace

// The formulation `--dynamics` asks for (docs/theory.md §4.9).
Formulation formulation(const Model& model, const std::string& dynamics) {
  if (dynamics != "auto" && dynamics != "lagrangian" && dynamics != "recursive")
    throw UsageError(
        fmt::format("dynamics: expected auto, lagrangian or recursive, got '{}'", dynamics));
  if (dynamics == "lagrangian") return Formulation::Lagrangian;
  const std::string why = recursive_unsuitable(model);
  if (dynamics == "recursive") {
    if (!why.empty())
      throw UsageError(
          fmt::format("--dynamics recursive: the articulated-body algorithm does "
                      "not apply to {}: {}; use --dynamics lagrangian",
                      model.file, why));
    return Formulation::Recursive;
  }
  return why.empty() ? Formulation::Recursive : Formulation::Lagrangian;
}

std::vector<std::pair<std::string, std::string>> split_assignments(
    const std::vector<std::string>& given, const std::string& option) {
  // The options split their values at commas: a piece inside a function's parentheses
  // (`theta=atan2(1`, `2)`) is joined back to the value it belongs to.
  std::vector<std::string> args;
  int depth = 0;
  for (const auto& piece : given) {
    if (depth > 0 && !args.empty())
      args.back() += "," + piece;
    else
      args.push_back(piece);
    for (char c : piece) depth += c == '(' || c == '[' ? 1 : c == ')' || c == ']' ? -1 : 0;
  }
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& s : args) {
    const auto eq = s.find('=');
    if (eq == std::string::npos) throw UsageError(option + " expects NAME=VALUE, got '" + s + "'");
    out.emplace_back(s.substr(0, eq), s.substr(eq + 1));
  }
  return out;
}

std::vector<std::pair<std::string, double>> evaluate_assignments(
    const std::vector<std::pair<std::string, std::string>>& given, const std::string& option,
    const std::map<std::string, double>& names) {
  std::vector<std::pair<std::string, double>> out;
  for (const auto& [name, text] : given) {
    try {
      out.emplace_back(name, evaluate_value_text(text, names));
    } catch (const ValueTextError& e) {
      throw UsageError(fmt::format("{}: expected a finite number after '{}=', got '{}': {}", option,
                                   name, text, e.what()));
    }
  }
  return out;
}

std::vector<std::pair<std::string, double>> parse_assignments(const std::vector<std::string>& args,
                                                              const std::string& option) {
  return evaluate_assignments(split_assignments(args, option), option, {});
}

ParameterOverrides parse_sets(const std::vector<std::string>& sets) {
  ParameterOverrides out;
  for (const auto& [name, value] : parse_assignments(sets, "--set")) out[name] = value;
  return out;
}

Prepared prepare(const std::string& path, const std::vector<std::string>& sets,
                 const std::vector<std::string>& initial, const std::string& initial_option,
                 const std::string& dynamics) {
  const ParameterOverrides overrides = parse_sets(sets);
  const GivenState initial_values{split_assignments(initial, initial_option), initial_option};
  std::string given;
  for (const auto& s : sets) given += (given.empty() ? "--set " : " --set ") + s;
  return prepare_checked(ModelSource{path, std::nullopt}, overrides, initial_values, dynamics,
                         "--set", given);
}

Prepared prepare_source(const ModelSource& source, const ParameterOverrides& overrides,
                        const std::string& dynamics,
                        const std::vector<std::pair<std::string, double>>& initial) {
  std::string given;
  for (const auto& [name, value] : overrides) {
    if (!std::isfinite(value))  // else a later check blames another parameter (issue 37 item 14)
      throw UsageError(fmt::format("set {}={}: expected a finite number", name, value));
    given += fmt::format("{}{}={}", given.empty() ? "set " : ", ", name, value);
  }
  GivenState given_initial{{}, "initial"};
  for (const auto& [name, value] : initial) {
    if (!std::isfinite(value))
      throw UsageError(fmt::format("initial {}={}: expected a finite number", name, value));
    given_initial.values.emplace_back(name, fmt::format("{:.17g}", value));  // read back exactly
  }
  return prepare_checked(source, overrides, given_initial, dynamics, "set", given);
}

void check_output(const std::string& path, const std::string& option) {
  try {
    check_writable(path);
  } catch (const std::runtime_error& e) {
    throw UsageError(fmt::format("{}: {}", option, e.what()));
  }
}

Model ModelSource::read(const ParameterOverrides& overrides, const StartValues& start) const {
  return text ? read_model_string(*text, path, overrides, nullptr, start)
              : read_model_file(path, overrides, start);
}

SimulationOptions simulation_options(const Model& model, const RunSettings& given) {
  SimulationOptions so;
  so.t_end = given.t_end.value_or(model.simulate.t_end);
  so.output_step = given.output_step.value_or(model.simulate.output_step);
  so.integrator.method = given.integrator.value_or(model.simulate.integrator);
  so.integrator.rtol = given.rtol.value_or(model.simulate.rtol);
  so.integrator.atol = given.atol.value_or(model.simulate.atol);
  so.integrator.step = given.step.value_or(model.simulate.step);
  so.integrator.max_order = given.max_order.value_or(model.simulate.max_order);
  so.project = model.stabilization.project;
  if (!(so.t_end > 0)) throw UsageError("--t-end must be positive");
  if (!(so.output_step > 0)) throw UsageError("--output-step must be positive");
  // Counts checked before anything is allocated (issue 37 item 3): the grid's samples, and the
  // fixed steps in one output interval.
  const double intervals = (so.t_end - so.t0) / so.output_step;
  if (!(intervals <= kMaxOutputIntervals))
    throw UsageError(fmt::format(
        "--output-step {:g} gives {:.3g} samples up to t_end = {:g}, more than the {:.0e} a run "
        "may keep; give a larger --output-step or a shorter --t-end",
        so.output_step, intervals + 1, so.t_end, kMaxOutputIntervals));
  const double fixed_steps = so.output_step / so.integrator.step;
  if (so.integrator.step > 0 && !(fixed_steps <= static_cast<double>(so.integrator.max_steps)))
    throw UsageError(fmt::format(
        "--step {:g} makes {:.3g} steps per output interval of {:g}, more than {}; give a larger "
        "--step",
        so.integrator.step, fixed_steps, so.output_step, so.integrator.max_steps));
  if (!(so.integrator.rtol > 0) || !(so.integrator.atol > 0))
    throw UsageError("tolerances must be positive");
  if (so.integrator.max_order < 1 || so.integrator.max_order > 5)
    throw UsageError(
        fmt::format("--max-order must be from 1 to 5 (the BDF methods' highest "
                    "order), got {}",
                    so.integrator.max_order));
  return so;
}

// docs/theory.md §8, machine code: `on` compiles before the run (and says at once when it cannot),
// `auto` runs the interpreter while a large model compiles in the background.
Evaluation evaluation_mode(const std::string& mode) {
  if (mode == "off") return Evaluation::Interpreter;
  if (mode == "on") return Evaluation::MachineCode;
  if (mode == "auto") return Evaluation::Background;
  throw UsageError("compile: expected auto, on or off, got '" + mode + "'");
}

bool choose_evaluation(Dynamics& dynamics, const std::string& mode,
                       std::function<bool()> interrupted) {
  const Evaluation evaluation = evaluation_mode(mode);
  if (evaluation == Evaluation::Interpreter) return true;
  MachineCodeOptions options;
  options.interrupted = std::move(interrupted);
  dynamics.set_evaluation(evaluation, options);
  return evaluation != Evaluation::MachineCode || dynamics.uses_machine_code();
}

}  // namespace lagrange::cli
