#pragma once
// Equations compiled to tapes: immutable, shareable across threads, parameters still symbolic.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/equations.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

/// Sizes, names and tapes of a derived model. All tapes share the input layout
/// [t, q(n), v(n), u(k), u̇(k), ü(k), p(np)] (see input_offset()).
struct CompiledModel {
  size_t n = 0, m = 0, k = 0, np = 0;
  std::vector<std::string> coordinate_names, constraint_names, output_names, input_names,
      parameter_names;
  std::vector<double> parameter_defaults;
  std::vector<double> q0, v0;  ///< initial state from the model
  std::vector<bool> fixed;     ///< coordinates kept by the initial-state projection

  /// Structural non-zeros: M lower triangle (i ≥ j) and G (row, column), in tape output order.
  std::vector<std::pair<size_t, size_t>> M_pattern, G_pattern;
  bool M_diagonal = false;  ///< M has no structural off-diagonal entries

  /// Outputs: M_pattern values, rhs = h + Q (n), q̇ (n), G_pattern values, c (m), Ċ (m), C (m).
  Tape dynamics;
  /// Outputs: T, U, then the model's outputs.
  Tape observables;
  /// Outputs: u (k), u̇ (k), ü (k) as functions of t and p.
  Tape inputs;

  size_t input_count() const { return 1 + 2 * n + 3 * k + np; }
  size_t q_offset() const { return 1; }
  size_t v_offset() const { return 1 + n; }
  size_t u_offset() const { return 1 + 2 * n; }
  size_t p_offset() const { return 1 + 2 * n + 3 * k; }
  /// Offsets of the blocks in the dynamics tape's outputs.
  size_t rhs_out() const { return M_pattern.size(); }
  size_t qdot_out() const { return rhs_out() + n; }
  size_t G_out() const { return qdot_out() + n; }
  size_t c_out() const { return G_out() + G_pattern.size(); }
  size_t Cdot_out() const { return c_out() + m; }
  size_t C_out() const { return Cdot_out() + m; }
};

/// Compile derived equations into tapes (common subexpressions shared, parameters kept as
/// tape inputs so that a new value needs no new derivation).
std::shared_ptr<const CompiledModel> compile(const Equations& eq);

}  // namespace lagrange
