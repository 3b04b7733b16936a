#pragma once
// Equations compiled to tapes: immutable, shareable across threads, parameters still symbolic.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/equations.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

/// One term of a load column: observable `observable` times a (when `acceleration` ≥ 0), λ (when
/// `multiplier` ≥ 0) or 1 (docs/theory.md §4.11).
struct LoadTerm {
  size_t observable = 0;
  int acceleration = -1, multiplier = -1;
};

/// A load column (Model::loads): one part is the value, three are a vector whose length it is.
struct LoadColumn {
  std::string name;
  std::vector<std::vector<LoadTerm>> parts;
};

/// Sizes, names and tapes of a derived model. All tapes share the input layout
/// [t, q(nq), v(nv), u(k), u̇(k), ü(k), p(np)] (see input_offset()). The last parameter of a
/// model with free bodies is `stabilization.gamma`, the SO(3) drift correction rate (§4.4).
struct CompiledModel {
  size_t nq = 0, nv = 0, m = 0, k = 0, np = 0;
  size_t plain = 0;  ///< leading coordinates with q̇ = v (position index = velocity index)
  std::vector<std::string> coordinate_names;  ///< nq: plain names, then `<body>.x`, `<body>.R11`, …
  std::vector<std::string> velocity_names;  ///< nv: `<name>_dot`, then `<body>.vx`, `<body>.wx`, …
  std::vector<std::string> constraint_names, output_names, input_names, parameter_names;
  std::vector<double> parameter_defaults;
  std::vector<bool> external_inputs;  ///< k: inputs a caller may set (Dynamics::hold_input)
  /// Reaction columns λ_c · scale (Model::reactions): names and constraint indices; their
  /// scales are the last observables.
  std::vector<std::string> reaction_names;
  std::vector<size_t> reaction_constraints;
  /// Load columns, recorded last; their coefficients follow the reactions' scales in observables.
  std::vector<LoadColumn> loads;
  std::vector<double> q0, v0;     ///< initial state from the model (nq, nv)
  std::vector<bool> fixed;        ///< nq: coordinates kept by the initial-state projection
  std::vector<size_t> rotations;  ///< per free body, the index in q of R11 (R row-major, 9 entries)
  std::vector<StopSpec> stop_when;  ///< the model's stop conditions (lagrange/stop_conditions.hpp)
  /// Conditions out of an element's domain (Model::fail_when): the run fails where one becomes
  /// true.
  std::vector<StopSpec> fail_when;
  /// Model::warn_when: the first sample where one holds adds a warning to the trajectory.
  std::vector<StopSpec> warn_when;
  /// stop_when, fail_when and warn_when compiled once, each to one tape over a trajectory row
  /// (trajectory_columns) and the parameters (compile_conditions, lagrange/stop_conditions.hpp):
  /// a run evaluates them without the symbolic layer.
  Tape stop_tape, fail_tape, warn_tape;
  /// T + U is a constant of motion (conserves_energy()): a run that changes it fails.
  bool conservative = false;

  /// Structural non-zeros: M lower triangle (i ≥ j), G (row, velocity column) and ∂C/∂q
  /// (row, coordinate column), in tape output order.
  std::vector<std::pair<size_t, size_t>> M_pattern, G_pattern, Cq_pattern;
  bool M_diagonal = false;  ///< M has no structural off-diagonal entries

  /// Outputs: M_pattern values, rhs = h + Q (nv), q̇ (nq), G_pattern values, c (m), Ċ (m),
  /// C (m), Cq_pattern values.
  Tape dynamics;
  /// Outputs: T, U, the model's outputs, the reactions' scales, then the loads' coefficients.
  Tape observables;
  /// Outputs: u (k), u̇ (k), ü (k) as functions of t and p.
  Tape inputs;

  size_t input_count() const { return 1 + nq + nv + 3 * k + np; }
  size_t q_offset() const { return 1; }
  size_t v_offset() const { return 1 + nq; }
  size_t u_offset() const { return 1 + nq + nv; }
  size_t p_offset() const { return 1 + nq + nv + 3 * k; }
  /// Offsets of the blocks in the dynamics tape's outputs.
  size_t rhs_out() const { return M_pattern.size(); }
  size_t qdot_out() const { return rhs_out() + nv; }
  size_t G_out() const { return qdot_out() + nq; }
  size_t c_out() const { return G_out() + G_pattern.size(); }
  size_t Cdot_out() const { return c_out() + m; }
  size_t C_out() const { return Cdot_out() + m; }
  size_t Cq_out() const { return C_out() + m; }
};

/// A model's initial state in the layout of its compiled form: plain coordinates, then each free
/// body's r and R (q0), their rates, then each free body's ṙ and ω (v0).
struct ModelInitialState {
  std::vector<double> q0, v0;
  std::vector<bool> fixed;        ///< as CompiledModel::fixed
  std::vector<size_t> rotations;  ///< as CompiledModel::rotations
};
ModelInitialState model_initial_state(const Model& model);

/// Compile derived equations into tapes (common subexpressions shared, parameters kept as
/// tape inputs so that a new value needs no new derivation).
std::shared_ptr<const CompiledModel> compile(const Equations& eq);

/// The column names simulate() produces for a compiled model.
std::vector<std::string> trajectory_columns(const CompiledModel& model);

/// `specs` (stop_when, fail_when or warn_when: `lhs < rhs` or `lhs > rhs`) compiled to one tape
/// over a row of `columns` (trajectory_columns(cm)), then cm's parameters: output i is g_i,
/// positive exactly when condition i holds. ModelError at the condition for an unknown name or a
/// vector-valued side. compile() makes cm's three.
Tape compile_conditions(const std::vector<StopSpec>& specs, const CompiledModel& cm,
                        const std::vector<std::string>& columns);

/// The expressions of `cm.dynamics`' outputs, in its output order (`cm` compiled from `eq`).
std::vector<GiNaC::ex> dynamics_expressions(const Equations& eq, const CompiledModel& cm);

}  // namespace lagrange
