#pragma once
// The explicit Runge–Kutta tables of ARKODE offered by name (`arkode:<name>`), and the table
// plain `arkode` uses at a given tolerance (chosen by the work–precision benchmark,
// docs/benchmarks.md).

#include <string>

namespace lagrange::integration {

/// An embedded ERK pair: ARKODE's table id (ARKODE_ERKTableID) and its order.
struct ErkTable {
  const char* name;  ///< the part after `arkode:`
  int id;            ///< ARKODE_ERKTableID
  int order;         ///< order of the propagated solution
};

/// The table `arkode:<name>` names, or null for an unknown name.
const ErkTable* find_erk_table(const std::string& name);

/// The table plain `arkode` uses at relative tolerance rtol.
const ErkTable& default_erk_table(double rtol);

}  // namespace lagrange::integration
