#pragma once
// A starting point read from a trajectory CSV (`guess: FILE.csv`, docs/theory.md §10, "Initial
// guess"): an earlier solution or a simulation, stretched over the horizon.

#include <optional>
#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"

namespace lagrange::collocation {

/// The file's states (q, v) at `times` and, per time, the named controls where the file has all
/// their columns (else none). Its time axis [0, t_last] is stretched onto [0, horizon], values
/// between rows are linear. std::invalid_argument naming the file for a malformed file or a
/// missing coordinate or rate column.
struct FileGuess {
  std::vector<std::vector<double>> states;
  std::optional<std::vector<std::vector<double>>> controls;
};
FileGuess read_file_guess(const std::string& path, const CompiledModel& cm,
                          const std::vector<std::string>& control_names,
                          const std::vector<double>& times, double horizon);

}  // namespace lagrange::collocation
