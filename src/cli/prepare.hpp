#pragma once
// Everything a command does before it writes anything: read the model (with --set values),
// derive, compile, and make the initial state consistent and regular.

#include <memory>
#include <string>
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

/// Reads `path` with the --set values applied by the reader, derives, compiles and checks the
/// initial state (ModelError for a mistake in the file). A --set naming no parameter, or one whose
/// value makes the model invalid when the file alone is not, is a UsageError (exit 2) that
/// names the --set and says what the model rejected and where it uses the value.
Prepared prepare(const std::string& path, const std::vector<std::string>& sets);

}  // namespace lagrange::cli
