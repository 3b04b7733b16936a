#pragma once
// The HTML report from the command line: `simulate --report` and `lagrange report`.

#include "cli/commands.hpp"
#include "cli/prepare.hpp"

namespace lagrange::cli {

/// Checks a report before the run: an .html name (UsageError otherwise) and the model's
/// `visual:` section (ModelError).
void check_report(const std::string& path, const Model& model);

/// Writes the report of a run of `p` to `path`; `wall_seconds` < 0 when unknown.
void write_run_report(const Prepared& p, const Trajectory& traj, const std::string& integrator,
                      double wall_seconds, const std::string& path);

}  // namespace lagrange::cli
