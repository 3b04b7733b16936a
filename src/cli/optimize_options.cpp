#include "cli/optimize_options.hpp"

#include <fmt/format.h>

#include "cli/prepare.hpp"

namespace lagrange::cli {

OptimizeOptions optimize_options(const Options& opt) {
  OptimizeOptions o;
  o.intervals = opt.intervals;
  o.degree = opt.degree;
  o.verbose = opt.verbose;
  o.hessian = opt.hessian == "exact"            ? HessianChoice::Exact
              : opt.hessian == "limited-memory" ? HessianChoice::LimitedMemory
                                                : HessianChoice::Auto;
  o.evaluation = evaluation_mode(opt.compile);  // docs/theory.md §8, as `simulate` chooses it
  for (const std::string& a : opt.ipopt) {
    const size_t eq = a.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError(fmt::format("expected --ipopt KEY=VALUE, got '{}'", a));
    o.ipopt.emplace_back(a.substr(0, eq), a.substr(eq + 1));
  }
  return o;
}

}  // namespace lagrange::cli
