// The HTML report: one file with the scene, the plot series, the equations, the parameters and
// the run statistics as JSON beside the inlined front-end (web/).

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "io/report_bundle.hpp"
#include "io/report_scene.hpp"
#include "lagrange/io.hpp"

namespace lagrange {

namespace {

/// LaTeX of `derive` up to about this many characters (whole blocks); the rest is named.
constexpr size_t kLatexLimit = 400000;

// A value with `digits` significant digits, so that it prints short.
double significant(double x, int digits) {
  if (!std::isfinite(x) || x == 0) return x;
  return io::round_decimals(x, digits - 1 - static_cast<int>(std::floor(std::log10(std::abs(x)))));
}

std::string group_of(const CompiledModel& cm, const std::string& column) {
  auto in = [&](const std::vector<std::string>& names) {
    return std::find(names.begin(), names.end(), column) != names.end();
  };
  if (in(cm.coordinate_names)) return "coordinates";
  if (in(cm.velocity_names)) return "rates";
  if (column == "kinetic" || column == "potential" || column == "energy") return "energy";
  if (in(cm.output_names)) return "outputs";
  if (in(cm.constraint_names)) return "multipliers";
  if (in(cm.reaction_names)) return "tensions";
  for (const LoadColumn& load : cm.loads)
    if (load.name == column) return "tensions";
  return "residuals";
}

nlohmann::json plot_series(const CompiledModel& cm, const Trajectory& traj,
                           const ReportLimits& limits) {
  const size_t nc = traj.columns.size();
  const std::vector<size_t> rows = io::sample_rows(
      traj.rows(),
      std::min(limits.max_plot_rows,
               std::max<size_t>(2, limits.max_plot_numbers / std::max<size_t>(nc, 1))));
  nlohmann::json series = nlohmann::json::array();
  std::vector<double> t;
  for (size_t r : rows) t.push_back(traj.data[r * nc]);
  for (size_t c = 1; c < nc; ++c) {
    std::vector<double> values;
    values.reserve(rows.size());
    for (size_t r : rows) values.push_back(significant(traj.data[r * nc + c], 6));
    series.push_back(
        {{"name", traj.columns[c]}, {"group", group_of(cm, traj.columns[c])}, {"values", values}});
  }
  return {{"t", t}, {"series", series}};
}

std::string limited_latex(const Equations& eq) {
  std::string tex = format_equations(eq, "latex");
  if (tex.size() <= kLatexLimit) return tex;
  const size_t cut = tex.rfind("\\end{align*}\n", kLatexLimit);
  const size_t keep = cut == std::string::npos ? 0 : cut + 13;
  return tex.substr(0, keep) +
         fmt::format("% {} more characters of equations: lagrange derive --format latex\n",
                     tex.size() - keep);
}

nlohmann::json statistics(const CompiledModel& cm, const Trajectory& traj, const ReportRun& run) {
  nlohmann::json s;
  s["status"] = traj.status_name();
  if (!traj.message.empty()) s["message"] = traj.message;
  if (!run.integrator.empty()) s["integrator"] = run.integrator;
  s["steps"] = traj.stats.steps;
  s["rhs_evaluations"] = traj.stats.rhs_evals;
  s["failed_steps"] = traj.stats.failed_steps;
  if (run.wall_seconds >= 0) s["wall_seconds"] = run.wall_seconds;
  if (run.derive_seconds >= 0) s["derive_seconds"] = run.derive_seconds;
  if (run.compile_seconds >= 0) s["compile_seconds"] = run.compile_seconds;
  s["coordinates"] = cm.nq;
  s["constraints"] = cm.m;
  const size_t rows = traj.rows();
  s["samples"] = rows;
  if (rows == 0) return s;
  s["t_start"] = traj.at(0, "t");
  s["t_end"] = traj.at(rows - 1, "t");
  const double e0 = traj.at(0, "energy"), e1 = traj.at(rows - 1, "energy");
  s["energy_start"] = e0;
  s["energy_end"] = e1;
  s["energy_drift"] = std::abs(e1 - e0) / std::max(std::abs(e0), 1e-300);
  const auto& cols = traj.columns;
  if (std::find(cols.begin(), cols.end(), "constraint_residual") != cols.end()) {
    double worst = 0;
    for (size_t r = 0; r < rows; ++r) worst = std::max(worst, traj.at(r, "constraint_residual"));
    s["max_constraint_residual"] = worst;
  }
  if (traj.rotation_drift > 0) s["rotation_drift"] = traj.rotation_drift;
  return s;
}

// JSON inside <script>: "</" must not close the element.
std::string script_safe(std::string text) {
  for (size_t at = text.find("</"); at != std::string::npos; at = text.find("</", at + 3))
    text.replace(at, 2, "<\\/");
  return text;
}

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '>')
      out += "&gt;";
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string report_scene_json(const Equations& eq, const CompiledModel& cm, const Trajectory& traj,
                              const std::vector<double>& parameters, const ReportLimits& limits) {
  return io::scene(eq, cm, traj, parameters, limits).dump();
}

ReportNotes write_report(const Equations& eq, const CompiledModel& cm, const Trajectory& traj,
                         const std::vector<double>& parameters, const ReportRun& run,
                         const std::string& path, const ReportLimits& limits) {
  const Model& model = *eq.model;
  nlohmann::json data;
  data["name"] = model.name;
  data["file"] = model.file;
  data["scene"] = io::scene(eq, cm, traj, parameters, limits);
  data["plots"] = plot_series(cm, traj, limits);
  data["latex"] = limited_latex(eq);
  nlohmann::json params = nlohmann::json::array();
  for (size_t i = 0; i < cm.parameter_names.size() && i < parameters.size(); ++i)
    params.push_back({{"name", cm.parameter_names[i]}, {"value", parameters[i]}});
  data["parameters"] = params;
  data["stats"] = statistics(cm, traj, run);
  const std::string html = fmt::format(
      "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<title>{} — lagrange report</title>\n<style>\n{}\n</style>\n</head>\n<body>\n"
      "<div id=\"app\"></div>\n"
      "<script type=\"application/json\" id=\"lagrange-data\">{}</script>\n"
      "<script>\n{}\n</script>\n</body>\n</html>\n",
      html_escape(model.name), io::report_style(), script_safe(data.dump()), io::report_script());
  write_file_atomically(path, html);
  ReportNotes out;
  if (data["scene"].contains("notes")) out.notes = data["scene"]["notes"];
  if (data["scene"].contains("mesh_bytes")) out.mesh_bytes = data["scene"]["mesh_bytes"];
  return out;
}

}  // namespace lagrange
