#include "cli/report_command.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "lagrange/report.hpp"

namespace lagrange::cli {

namespace {
/// Largest recursive model whose report derives the Lagrangian form for display (the Panda's
/// seven joints take 0.7 s; twelve joints of a chain about 2 s).
constexpr size_t kReportLagrangianJoints = 12;
}  // namespace

void check_report(const std::string& path, const Model& /*model*/) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext != ".html" && ext != ".htm")
    throw UsageError(fmt::format("--report {}: expected a file name ending in .html", path));
}

ReportNotes write_run_report(const Prepared& p, const Trajectory& traj,
                             const std::string& integrator, double wall_seconds,
                             const std::string& path) {
  ReportRun run;
  run.integrator = integrator;
  run.wall_seconds = wall_seconds;
  run.derive_seconds = p.derive_seconds;
  run.compile_seconds = p.compile_seconds;
  // The recursive formulation has no M or h to show (docs/theory.md §4.9): for trees small
  // enough to derive at once, the report shows the Lagrangian form of the same model.
  if (p.equations.recursive && p.compiled->nv <= kReportLagrangianJoints)
    return write_report(derive(*p.model), *p.compiled, traj, p.dynamics->parameters(), run, path);
  return write_report(p.equations, *p.compiled, traj, p.dynamics->parameters(), run, path);
}

void print_report_notes(const ReportNotes& notes, const std::string& path, bool quiet) {
  for (const std::string& n : notes.notes) fmt::print(stderr, "lagrange: note: {}\n", n);
  if (!quiet && notes.mesh_bytes > 0)
    fmt::print("  {} embeds {:.1f} KiB of URDF meshes\n", path,
               static_cast<double>(notes.mesh_bytes) / 1024);
}

int run_report(const Options& opt) {
  check_output(opt.report, "-o");  // before the model is read (issue 37 item 1)
  const Prepared p = prepare(opt.model, opt.sets);
  check_report(opt.report, *p.model);
  Trajectory traj;
  try {
    traj = read_trajectory_csv(opt.trajectory);
  } catch (const std::runtime_error& e) {
    throw UsageError(e.what());
  }
  if (traj.rows() == 0)
    throw UsageError(fmt::format("{}: the trajectory has no samples", opt.trajectory));
  ReportNotes notes;
  try {
    notes = write_run_report(p, traj, "", -1, opt.report);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).rfind("the trajectory has no column", 0) == 0)
      throw UsageError(fmt::format("{}: {}", opt.trajectory, e.what()));
    throw;
  }
  if (!opt.quiet)
    fmt::print("wrote {} ({} samples of {})\n", opt.report, traj.rows(), p.model->name);
  print_report_notes(notes, opt.report, opt.quiet);
  return 0;
}

}  // namespace lagrange::cli
