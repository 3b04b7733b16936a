// Reading a saved trajectory back (`lagrange report MODEL traj.csv`): the CSV of
// write_trajectory_csv and, when present, its `.json` status sidecar.

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "lagrange/report.hpp"

namespace lagrange {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

void read_sidecar(const std::string& path, Trajectory& traj) {
  std::ifstream in(path);
  if (!in) return;
  nlohmann::json side;
  try {
    side = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception&) {
    return;  // a damaged sidecar leaves the statistics unknown; the CSV is what is shown
  }
  const std::string status = side.value("status", "complete");
  if (status == "failed") traj.status = Trajectory::Status::Failed;
  if (status == "interrupted") traj.status = Trajectory::Status::Interrupted;
  traj.message = side.value("reason", "");
  traj.stats.steps = side.value("steps", 0L);
  traj.stats.rhs_evals = side.value("rhs_evaluations", 0L);
  traj.stats.failed_steps = side.value("failed_steps", 0L);
  traj.rotation_drift = side.value("rotation_drift", 0.0);
}

}  // namespace

Trajectory read_trajectory_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(fmt::format("cannot open the trajectory '{}'", path));
  Trajectory traj;
  std::string line;
  if (!std::getline(in, line) || line.rfind("t,", 0) != 0)
    throw std::runtime_error(
        fmt::format("{}:1: expected a trajectory CSV whose header starts with 't,'", path));
  traj.columns = split(line);
  size_t number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    const std::vector<std::string> cells = split(line);
    if (cells.size() != traj.columns.size())
      throw std::runtime_error(fmt::format("{}:{}: expected {} values, got {}", path, number,
                                           traj.columns.size(), cells.size()));
    for (const auto& cell : cells) {
      char* end = nullptr;
      const double x = std::strtod(cell.c_str(), &end);
      if (cell.empty() || *end != '\0' || !std::isfinite(x))  // simulate writes finite values
        throw std::runtime_error(
            fmt::format("{}:{}: expected a finite number, got '{}'", path, number, cell));
      traj.data.push_back(x);
    }
  }
  read_sidecar(path + ".json", traj);
  return traj;
}

}  // namespace lagrange
