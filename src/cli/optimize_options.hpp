#pragma once
// The command line's optimisation settings (--intervals, --degree, --hessian, --ipopt), shared
// by `lagrange optimize` and `lagrange sweep --optimize`.

#include "cli/commands.hpp"
#include "lagrange/optimize.hpp"

namespace lagrange::cli {

/// OptimizeOptions from the parsed command line; UsageError for an --ipopt without KEY=VALUE.
OptimizeOptions optimize_options(const Options& opt);

}  // namespace lagrange::cli
