#pragma once
// The HTML report (README.md, "Watching a model move"): one self-contained file with a 3-D
// animation of the scene, plots of the trajectory, the equations and the run statistics.

#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

/// How a run went, for the report's statistics table.
struct ReportRun {
  std::string integrator;    ///< method name, or "" when unknown (a saved trajectory)
  double wall_seconds = -1;  ///< simulation wall time; negative when unknown
  double derive_seconds = -1, compile_seconds = -1;
};

/// Samples kept for display: at most this many animation frames and plot rows (docs).
struct ReportLimits {
  size_t max_scene_numbers = 600000;  ///< frames × (3 per point + 12 per body)
  size_t max_frames = 2000;
  size_t max_plot_numbers = 600000;  ///< plot rows × columns
  size_t max_plot_rows = 2000;
};

/// The scene of a trajectory as JSON: points (particles sized by mass, fixed points, anchors),
/// bodies (origin, rotation, shape), segments (springs, dampers, rigid links found as constant
/// distances), trails, the up axis and the plane of a planar model, and positions at the
/// decimated frames. `parameters` are the values the run used (CompiledModel parameter order).
std::string report_scene_json(const Equations& eq, const CompiledModel& cm, const Trajectory& traj,
                              const std::vector<double>& parameters,
                              const ReportLimits& limits = {});

/// What a report drew otherwise than its model says (a URDF link whose mesh is missing, drawn
/// from its inertia), one line each, and the bytes of URDF meshes it embeds.
struct ReportNotes {
  std::vector<std::string> notes;
  size_t mesh_bytes = 0;
};

/// Writes the report of `traj` to `path` (atomically): the scene, the trajectory's columns
/// (decimated), the LaTeX of `derive`, the parameters and the run statistics, with the
/// front-end (three.js, uPlot, KaTeX) inlined so that the file opens offline.
ReportNotes write_report(const Equations& eq, const CompiledModel& cm, const Trajectory& traj,
                         const std::vector<double>& parameters, const ReportRun& run,
                         const std::string& path, const ReportLimits& limits = {});

/// Reads a trajectory CSV written by write_trajectory_csv (and its `.json` sidecar when present:
/// status and step counts). std::runtime_error naming the file and line for a malformed file.
Trajectory read_trajectory_csv(const std::string& path);

}  // namespace lagrange
