#pragma once
// Everything a command does before it writes anything: read the model (with --set values),
// derive, compile, and make the initial state consistent and regular.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/simulation.hpp"

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
};

/// `--set NAME=VALUE` arguments as overrides; UsageError for a missing '=' or a value that is
/// not a finite number.
ParameterOverrides parse_sets(const std::vector<std::string>& sets);

/// `NAME=VALUE` arguments of `option` in order; UsageError for a missing '=' or a value that is
/// not a finite number.
std::vector<std::pair<std::string, double>> parse_assignments(const std::vector<std::string>& args,
                                                              const std::string& option);

/// Reads `path` with the --set values applied by the reader, derives, compiles and checks the
/// initial state (ModelError for a mistake in the file). A --set naming no parameter, or one whose
/// value makes the model invalid when the file alone is not, is a UsageError (exit 2) that
/// names the --set and says what the model rejected and where it uses the value. `initial`
/// (NAME=VALUE of the option `initial_option`) replaces the file's initial value of a coordinate
/// or of a velocity `NAME_dot` before the state is made consistent; an unknown name is a
/// UsageError naming it. `dynamics` chooses the Formulation: "lagrangian", "recursive" (a
/// UsageError saying why when the model cannot take it) or "auto" (recursive where it applies:
/// faster to derive and per call at every size measured, docs/benchmarks.md).
/// The formulation `--dynamics` names for `model` ("lagrangian", "recursive" or "auto", as for
/// prepare); a UsageError saying why when "recursive" does not apply.
Formulation formulation(const Model& model, const std::string& dynamics);

Prepared prepare(const std::string& path, const std::vector<std::string>& sets,
                 const std::vector<std::string>& initial = {},
                 const std::string& initial_option = "--initial",
                 const std::string& dynamics = "lagrangian");

}  // namespace lagrange::cli
