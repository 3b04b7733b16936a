#include "cli/plot_check.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "cli/commands.hpp"

namespace lagrange::cli {

PlotFormat checked_plot_format(const std::string& path,
                               const std::function<std::string(PlotFormat)>& instead) {
  PlotFormat format;
  try {
    format = plot_format(path);
  } catch (const std::invalid_argument& e) {
    throw UsageError(fmt::format("--plot: {}", e.what()));
  }
  if (!plot_format_available(format))
    throw UsageError(fmt::format(
        "--plot {}: gnuplot with the '{}' terminal is needed and was not found (see gnuplot -e "
        "\"set terminal\"); install it, or {}",
        path, gnuplot_terminal(format), instead(format)));
  return format;
}

}  // namespace lagrange::cli
