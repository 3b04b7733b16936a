#pragma once
// Everything a command does before it writes anything: read the model (with --set values),
// derive, compile, and make the initial state consistent and regular.

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {
class DynamicsJacobian;
}

namespace lagrange::cli {

/// A model ready to run: its equations, tapes, a workspace at its parameter values and a
/// consistent initial state (q, v).
struct Prepared {
  std::unique_ptr<const Model> model;  ///< on the heap: `equations` points into it
  Equations equations;
  std::shared_ptr<const CompiledModel> compiled;
  std::unique_ptr<Dynamics> dynamics;
  std::vector<double> q, v;
  InitialConsistency initial;
  double derive_seconds = 0.0, compile_seconds = 0.0;
  /// The exact Jacobian's tape, derived by the first jacobian_source() that needs it and shared
  /// by every run of the model after it (a cache: not part of the model's value).
  mutable std::shared_ptr<const DynamicsJacobian> jacobian;
};

/// What cvode:jacobian and auto integrate on (SimulationOptions::jacobian_source), for every
/// run, Stepper and sweep case of `p`: the DynamicsJacobian derived once and kept in `p`, bound
/// to each run's own workspace. Empty for other methods, and for auto when the model is in the
/// recursive formulation (auto then runs DOP853); for cvode:jacobian there a UsageError ending in
/// `lagrangian_hint` (how to derive the Lagrangian form). Not thread-safe (GiNaC): call it before
/// runs start.
JacobianSource jacobian_source(const Prepared& p, const std::string& method,
                               const std::string& lagrangian_hint = "add --dynamics lagrangian");

/// Where a model comes from: the file `path`, or YAML `text` that messages label `path` (the
/// Python module's loads(), and a pickled model).
struct ModelSource {
  std::string path;
  std::optional<std::string> text;
  /// read_model_file(path) or read_model_string(*text, path) with `overrides`, starting from
  /// `start`.
  Model read(const ParameterOverrides& overrides, const StartValues& start = {}) const;
};

/// check_writable(path) as a command-line mistake: UsageError "OPTION: cannot write …" (exit 2)
/// unless a new file can be created at `path` (an existing device, FIFO, socket or directory
/// cannot).
void check_output(const std::string& path, const std::string& option);

/// `--set NAME=VALUE` arguments as overrides; UsageError for a missing '=' or a value that is
/// not a finite number.
ParameterOverrides parse_sets(const std::vector<std::string>& sets);

/// `NAME=VALUE` arguments of `option` as (NAME, VALUE text) in order, pieces of one value that a
/// comma-separated option split inside parentheses joined again; UsageError for a missing '='.
std::vector<std::pair<std::string, std::string>> split_assignments(
    const std::vector<std::string>& args, const std::string& option);

/// Each VALUE text read as the model file reads a value (evaluate_value_text: numbers, pi,
/// functions and `names`); UsageError naming `option`, the NAME and what is wrong otherwise.
std::vector<std::pair<std::string, double>> evaluate_assignments(
    const std::vector<std::pair<std::string, std::string>>& given, const std::string& option,
    const std::map<std::string, double>& names);

/// `NAME=VALUE` arguments of `option` in order, each VALUE an expression of numbers and pi
/// (`pi/10`); UsageError for a missing '=' or a value that is not a finite number.
std::vector<std::pair<std::string, double>> parse_assignments(const std::vector<std::string>& args,
                                                              const std::string& option);

/// Reads `path` with the --set values applied by the reader, derives, compiles and checks the
/// initial state (ModelError for a mistake in the file). A --set naming no parameter, or one whose
/// value makes the model invalid when the file alone is not, is a UsageError (exit 2) that
/// names the --set and says what the model rejected and where it uses the value. `initial`
/// (NAME=VALUE of the option `initial_option`, VALUE an expression of numbers, pi and the
/// model's parameters) replaces the file's initial value of a coordinate
/// or of a velocity `NAME_dot` before the state is made consistent; an unknown name is a
/// UsageError naming it. `dynamics` chooses the Formulation: "lagrangian", "recursive" (a
/// UsageError saying why when the model cannot take it) or "auto" (recursive where it applies:
/// faster to derive and per call at every size measured, docs/benchmarks.md).
/// The formulation `--dynamics` names for `model` ("lagrangian", "recursive" or "auto", as for
/// prepare); a UsageError saying why when "recursive" does not apply, or naming another word.
Formulation formulation(const Model& model, const std::string& dynamics);

Prepared prepare(const std::string& path, const std::vector<std::string>& sets,
                 const std::vector<std::string>& initial = {},
                 const std::string& initial_option = "--initial",
                 const std::string& dynamics = "lagrangian");

/// As prepare() for a source with overrides and initial values already parsed (the Python
/// module's load): the same ModelError and UsageError, the latter naming the values as
/// "set NAME=VALUE" and "initial: …". `initial` replaces coordinates and velocities NAME_dot.
Prepared prepare_source(const ModelSource& source, const ParameterOverrides& overrides,
                        const std::string& dynamics = "auto",
                        const std::vector<std::pair<std::string, double>>& initial = {});

/// Simulation settings a caller gives (command-line options, Python keywords); unset ones keep
/// the model file's `simulate:` values.
struct RunSettings {
  std::optional<double> t_end, output_step, rtol, atol, step;
  std::optional<std::string> integrator;
  std::optional<int> max_order;  ///< the BDF methods' highest order, 1 to 5
};

/// The model's `simulate:` settings with `given` applied and projection as the model says;
/// UsageError for a non-positive end time, output step or tolerance.
SimulationOptions simulation_options(const Model& model, const RunSettings& given);

/// The evaluation a `--compile` word names (docs/theory.md §8): "off" Interpreter, "on"
/// MachineCode, "auto" Background; UsageError for another word.
Evaluation evaluation_mode(const std::string& mode);

/// What evaluates the tapes (docs/theory.md §8): "off" the interpreter, "on" machine code at once
/// (false when it could not be had, evaluation_note() says why), "auto" machine code compiled in
/// the background for large tapes; UsageError for another word. `interrupted`, polled while "on"
/// compiles, stops the compiler when it returns true (MachineCodeOptions::interrupted).
bool choose_evaluation(Dynamics& dynamics, const std::string& mode,
                       std::function<bool()> interrupted = nullptr);

}  // namespace lagrange::cli
