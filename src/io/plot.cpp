#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <string>

#include "lagrange/io.hpp"

namespace lagrange {

namespace {

// A gnuplot single-quoted string (no escapes inside; a quote is doubled).
std::string literal(const std::string& s) {
  std::string r = "'";
  for (char c : s) r += c == '\'' ? std::string("''") : std::string(1, c);
  return r + "'";
}

// Enhanced-text label: underscores and carets shown literally, not as sub/superscripts.
std::string label(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '_' || c == '^' || c == '{' || c == '}' || c == '@' || c == '&') r += '\\';
    r += c;
  }
  return literal(r);
}

}  // namespace

PlotFormat plot_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".svg") return PlotFormat::Svg;
  if (ext == ".png") return PlotFormat::Png;
  throw std::invalid_argument("expected a plot file ending in .svg or .png, got '" + path + "'");
}

const char* gnuplot_terminal(PlotFormat format) {
  return format == PlotFormat::Png ? "pngcairo" : "svg";
}

// `gnuplot -e "set terminal"` lists one terminal per line: "  pngcairo  png terminal based on …".
bool plot_format_available(PlotFormat format) {
  FILE* pipe = popen("gnuplot -e 'set terminal' 2>&1", "r");
  if (pipe == nullptr) return false;
  std::string listing;
  char buf[4096];
  for (size_t got; (got = std::fread(buf, 1, sizeof buf, pipe)) > 0;) listing.append(buf, got);
  if (pclose(pipe) != 0) return false;
  std::istringstream lines(listing);
  for (std::string line, name; std::getline(lines, line);)
    if (std::istringstream(line) >> name && name == gnuplot_terminal(format)) return true;
  return false;
}

namespace {

// Runs gnuplot on `script`, which writes `tmp`; renamed to `path` on success.
void run_gnuplot(const std::string& script, const std::string& tmp, const std::string& path,
                 PlotFormat format) {
  FILE* pipe = popen("gnuplot 2>&1", "w");
  if (pipe == nullptr) throw std::runtime_error("cannot start gnuplot");
  std::fwrite(script.data(), 1, script.size(), pipe);
  const int status = pclose(pipe);
  if (status != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error(
        fmt::format("gnuplot failed (is gnuplot installed, with the '{}' "
                    "terminal?) while plotting '{}'",
                    gnuplot_terminal(format), path));
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename '" + tmp + "' to '" + path + "'");
}

// The terminal, output and title lines of a plot into `tmp`.
std::string preamble(PlotFormat format, const std::string& tmp, const std::string& title) {
  const char* terminal = format == PlotFormat::Png
                             ? "set terminal pngcairo size 900,500 enhanced font 'sans,10' "
                               "background '#ffffff'\n"
                             : "set terminal svg size 900,500 dynamic enhanced font 'sans,12' "
                               "background '#ffffff'\n";
  return terminal + fmt::format("set output {}\nset title {}\nset grid\nset key outside right\n",
                                literal(tmp), label(title));
}

}  // namespace

// Drives gnuplot through a pipe with inline data blocks ($data << EOD), output to a
// temporary name renamed on success.
void plot_trajectory(const Trajectory& traj, const std::vector<std::string>& columns,
                     const std::string& path, const std::string& title) {
  const PlotFormat format = plot_format(path);
  std::vector<size_t> idx;
  for (const auto& c : columns) idx.push_back(traj.column_index(c));
  create_parent_directories(path);
  const std::string tmp = path + ".part";
  std::string script = preamble(format, tmp, title) + "set xlabel 't [s]'\n";
  script += "$data << EOD\n";
  const size_t nc = traj.columns.size();
  for (size_t r = 0; r < traj.rows(); ++r) {
    script += fmt::format("{:.10g}", traj.data[r * nc]);
    for (size_t i : idx) script += fmt::format(" {:.10g}", traj.data[r * nc + i]);
    script += '\n';
  }
  script += "EOD\nplot ";
  for (size_t k = 0; k < idx.size(); ++k)
    script += fmt::format("{}$data using 1:{} with lines lw 2 title {}", k ? ", " : "", k + 2,
                          label(columns[k]));
  script += "\nset output\n";
  run_gnuplot(script, tmp, path, format);
}

void plot_columns(const std::vector<std::string>& names, const std::vector<double>& table,
                  const std::string& path, const std::string& title) {
  const PlotFormat format = plot_format(path);
  const size_t nc = names.size();
  if (nc < 2 || table.size() % nc != 0)
    throw std::invalid_argument("plot_columns: an x column, at least one y column, whole rows");
  create_parent_directories(path);
  const std::string tmp = path + ".part";
  std::string script =
      preamble(format, tmp, title) + fmt::format("set xlabel {}\n", label(names[0]));
  // One data block per curve: a row whose value is not finite (a case that failed) is left
  // out of that curve rather than breaking it.
  for (size_t k = 1; k < nc; ++k) {
    script += fmt::format("$curve{} << EOD\n", k);
    for (size_t r = 0; r < table.size() / nc; ++r)
      if (std::isfinite(table[r * nc]) && std::isfinite(table[r * nc + k]))
        script += fmt::format("{:.10g} {:.10g}\n", table[r * nc], table[r * nc + k]);
    script += "EOD\n";
  }
  script += "plot ";
  for (size_t k = 1; k < nc; ++k)
    script += fmt::format("{}$curve{} using 1:2 with linespoints lw 2 pt 7 title {}",
                          k > 1 ? ", " : "", k, label(names[k]));
  script += "\nset output\n";
  run_gnuplot(script, tmp, path, format);
}

}  // namespace lagrange
