#pragma once
// What `trim` varies and holds, from the command line (`lagrange trim`, `linearize --at-trim`).

#include <string>
#include <vector>

#include "cli/commands.hpp"
#include "cli/prepare.hpp"
#include "lagrange/analysis.hpp"

namespace lagrange::cli {

/// The names in --free that are model inputs or parameters (joint torques, say): what the
/// DynamicsJacobian for trim must differentiate by.
std::vector<std::string> trim_inputs(const CompiledModel& cm, const Options& opt);

/// TrimOptions from --free, --fix, --steady and --tol at the state (q, v): --steady holds the
/// named plain rates NAME_dot, --free names the coordinates, held rates and inputs (among
/// `inputs`, the Jacobian's) trim varies (default: every coordinate that does not move at a
/// held rate), --fix removes names from them. UsageError naming an unknown or unusable name and
/// saying what was expected.
TrimOptions trim_options(const CompiledModel& cm, const std::vector<double>& q,
                         const std::vector<double>& v, const Options& opt,
                         const std::vector<std::string>& inputs);

/// Trim `p` from its initial state with `options` on `jac` (p's derivatives), leaving the found
/// state in p.q, p.v (and free inputs' values in p.dynamics).
TrimResult trim_prepared(Prepared& p, const DynamicsJacobian& jac, const TrimOptions& options);

/// "equilibrium found by Levenberg–Marquardt in 3 iterations, max |acceleration| = 1e-12
/// (tolerance 1e-9)" and, for a steady state, whether it stays steady (max |da/dt| ≤ tol): what
/// `trim` and `linearize --at-trim` print first.
std::string trim_summary(const TrimResult& r, bool steady, double tol);

}  // namespace lagrange::cli
