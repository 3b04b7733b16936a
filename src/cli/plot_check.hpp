#pragma once
// --plot FILE checked before a run: a known format whose gnuplot terminal is installed.

#include <functional>
#include <string>

#include "lagrange/io.hpp"

namespace lagrange::cli {

/// The format of `path`, or UsageError naming the option and, when gnuplot lacks the format's
/// terminal, what the user can do instead (`instead` of the format).
PlotFormat checked_plot_format(const std::string& path,
                               const std::function<std::string(PlotFormat)>& instead);

}  // namespace lagrange::cli
