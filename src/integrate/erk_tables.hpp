#pragma once
// The explicit Runge–Kutta tables of ARKODE offered by name (`arkode:<name>`), and the table
// plain `arkode` uses at a given tolerance (chosen by the work–precision benchmark,
// docs/benchmarks.md).

#include <string>

#include "integrate/erk_coefficients.hpp"

namespace lagrange::integration {

/// An embedded ERK pair: one of ARKODE's tables (ARKODE_ERKTableID) or published coefficients
/// ARKODE does not ship (erk_coefficients.hpp).
struct ErkTable {
  const char* name;                               ///< the part after `arkode:`
  int id;                                         ///< ARKODE_ERKTableID, ARKODE_ERK_NONE for own
  int order;                                      ///< order of the propagated solution
  const ButcherCoefficients& (*own)() = nullptr;  ///< the coefficients when id is ARKODE_ERK_NONE
};

/// The table `arkode:<name>` names, or null for an unknown name.
const ErkTable* find_erk_table(const std::string& name);

/// The table plain `arkode` uses at relative tolerance rtol.
const ErkTable& default_erk_table(double rtol);

}  // namespace lagrange::integration
