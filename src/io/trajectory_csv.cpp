#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "lagrange/io.hpp"

namespace lagrange {

void write_trajectory_csv(const Trajectory& traj, const std::string& path) {
  std::string text;
  const size_t nc = traj.columns.size();
  for (size_t c = 0; c < nc; ++c) text += (c ? "," : "") + traj.columns[c];
  text += '\n';
  for (size_t r = 0; r < traj.rows(); ++r) {
    for (size_t c = 0; c < nc; ++c) {
      if (c) text += ',';
      fmt::format_to(std::back_inserter(text), "{:.17g}", traj.data[r * nc + c]);
    }
    text += '\n';
  }
  nlohmann::json side;
  side["status"] = traj.status_name();
  if (!traj.message.empty()) side["reason"] = traj.message;
  if (traj.status == Trajectory::Status::Failed) side["failure_time"] = traj.failure_time;
  if (!traj.stopped_by.empty()) {
    side["stopped_by"] = traj.stopped_by;
    side["stop_time"] = traj.stop_time;
  }
  side["rows"] = traj.rows();
  if (traj.rows() > 0) side["t_last"] = traj.data[(traj.rows() - 1) * nc];
  side["steps"] = traj.stats.steps;
  side["rhs_evaluations"] = traj.stats.rhs_evals;
  side["failed_steps"] = traj.stats.failed_steps;
  if (traj.rotation_drift > 0) side["rotation_drift"] = traj.rotation_drift;
  if (!traj.notes.empty()) side["notes"] = traj.notes;
  if (!traj.warnings.empty()) side["warnings"] = traj.warnings;
  side["csv_bytes"] = text.size();  // the file this sidecar describes (issue 25 item 1)
  write_file_with_sidecar(path, text, side.dump(2) + "\n");
}

}  // namespace lagrange
