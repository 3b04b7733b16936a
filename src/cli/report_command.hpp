#pragma once
// The HTML report from the command line: `simulate --report` and `lagrange report`.

#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "lagrange/report.hpp"

namespace lagrange::cli {

/// Checks a report's file name before the run: .html (UsageError otherwise). The model's
/// `visual:` section, which the report draws from, was checked by the reader that made `model`.
void check_report(const std::string& path, const Model& model);

/// Writes the report of a run of `p` to `path`; `wall_seconds` < 0 when unknown. Returns what
/// it drew otherwise than the model says and the meshes it embedded.
ReportNotes write_run_report(const Prepared& p, const Trajectory& traj,
                             const std::string& integrator, double wall_seconds,
                             const std::string& path);

/// The report's notes on stderr ("lagrange: note: …") and, when it embeds meshes, their size on
/// stdout after "wrote PATH" (unless quiet).
void print_report_notes(const ReportNotes& notes, const std::string& path, bool quiet);

}  // namespace lagrange::cli
