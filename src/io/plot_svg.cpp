#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
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

// Drives gnuplot through a pipe with inline data blocks ($data << EOD), output to a
// temporary name renamed on success.
void plot_trajectory_svg(const Trajectory& traj, const std::vector<std::string>& columns,
                         const std::string& path, const std::string& title) {
  std::vector<size_t> idx;
  for (const auto& c : columns) idx.push_back(traj.column_index(c));
  const std::string tmp = path + ".part";
  std::string script = fmt::format(
      "set terminal svg size 900,500 dynamic enhanced font 'sans,12' background '#ffffff'\n"
      "set output {}\nset title {}\nset xlabel 't [s]'\nset grid\nset key outside right\n",
      literal(tmp), label(title));
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
  FILE* pipe = popen("gnuplot 2>&1", "w");
  if (pipe == nullptr) throw std::runtime_error("cannot start gnuplot");
  std::fwrite(script.data(), 1, script.size(), pipe);
  const int status = pclose(pipe);
  if (status != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("gnuplot failed (is gnuplot-nox installed?) while plotting '" + path +
                             "'");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename '" + tmp + "' to '" + path + "'");
}

}  // namespace lagrange
