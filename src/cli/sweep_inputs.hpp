#pragma once
// The cases' inputs of a study on a prepared model, for `lagrange sweep` and Python's
// lagrange.sweep alike: from one traced read of the model file when it can give them
// (docs/theory.md §9.4), else from each case's own read.

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli/prepare.hpp"
#include "lagrange/sweep.hpp"

namespace lagrange::cli {

/// A case's values by parameter name (the study's varied parameters).
using CaseValues = std::vector<std::pair<std::string, double>>;

/// How a study's cases get their inputs: the source and the values every case shares (`fixed`,
/// --set), and what a case's model read becomes (its settings, its Jacobian source).
struct CaseInputSource {
  ModelSource source;
  ParameterOverrides fixed;
  std::function<sweep::CaseInput(const Model&)> inputs_of;
};

/// Case `values`' inputs from the model file read with them, or why the model rejects them (a
/// value it refuses, one that changes its structure). Not thread-safe (GiNaC).
sweep::CaseRead read_case_inputs(const CaseInputSource& from, const CaseValues& values);

/// The cases' inputs from one read (docs/theory.md §9.4), or why every case is read.
struct StudyReplay {
  std::optional<sweep::ReplayedInputs> inputs;
  std::string not_replayed;  ///< why not (when `inputs` is empty)
  std::string warning;       ///< the check read disagreed with the replay (please report)
  size_t reads = 0;          ///< model reads it made (the traced one and the check)
};

/// Reads the model once with `cases`' first values, following the parameters they name (every
/// case names the same ones); when every use of their values can be repeated, the inputs of
/// the last case the replay gives are also read from the file and must agree bit for bit, else
/// every case is read (a use the trace missed). Not thread-safe (GiNaC); the result's `inputs`
/// is.
StudyReplay replay_study(const CaseInputSource& from, const std::vector<CaseValues>& cases);

}  // namespace lagrange::cli
