#pragma once
// Internals of the HTML report: the scene evaluated at display frames, and decimation.

#include <nlohmann/json.hpp>
#include <vector>

#include "lagrange/report.hpp"

namespace lagrange::io {

/// `keep` row indices spread evenly over [0, rows), always with the first and the last.
std::vector<size_t> sample_rows(size_t rows, size_t keep);

/// `x` rounded to `decimals` decimal places (negative: to tens, hundreds…) so that it prints
/// short; non-finite values unchanged.
double round_decimals(double x, int decimals);

/// The scene of report_scene_json as a JSON value.
nlohmann::json scene(const Equations& eq, const CompiledModel& cm, const Trajectory& traj,
                     const std::vector<double>& parameters, const ReportLimits& limits);

/// Rigid links: pairs of points at a constant, non-zero distance over all frames with at least
/// one of them moving. `pos[f][i]` is point i at frame f; `exclude` pairs are left out (springs);
/// a link that runs through a third point in line with it is dropped, and at most `max_links`
/// (the shortest) are kept.
std::vector<std::pair<size_t, size_t>> rigid_links(
    const std::vector<std::vector<std::array<double, 3>>>& pos, double extent,
    const std::vector<std::pair<size_t, size_t>>& exclude, size_t max_links);

}  // namespace lagrange::io
