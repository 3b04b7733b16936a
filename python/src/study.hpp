#pragma once
// The cases of a parameter study run on a loaded model (lagrange.sweep, python/lagrange/study.py):
// the engine `lagrange sweep` uses (include/lagrange/sweep.hpp).

#include <pybind11/pybind11.h>

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lagrange/optimize.hpp"
#include "model.hpp"

namespace lagrange::python {

/// Each case (parameter values by name) run on `m`'s compiled model as `lagrange sweep` runs it,
/// with the GIL released while the cases run: (rows, reads), one dict per case with its values,
/// status, reason, failure_time, the metrics (specs as for `--metric`) and wall_s, and how many
/// times the model file was read for them (cases' inputs come from one read kept with `m` when
/// it gives them). ValueError before any case runs for an unknown parameter or a malformed or
/// unknown metric; `check_only` stops there.
pybind11::tuple run_cases(const PyModel& m, const std::vector<std::map<std::string, double>>& cases,
                          const std::vector<std::string>& metrics, const cli::RunSettings& settings,
                          bool check_only);

/// The cases of an optimisation study (lagrange.sweep(optimize=True); docs/sweeps.md "Optimal
/// control: a power curve"), solved one after another here, each started from the nearest
/// solved case: one dict per case, in case order.
pybind11::list optimize_cases(const PyModel& m,
                              const std::vector<std::map<std::string, double>>& cases,
                              const std::vector<std::string>& metrics,
                              const OptimizeOptions& options);

}  // namespace lagrange::python
