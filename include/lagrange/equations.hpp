#pragma once
// Derived equations of motion (docs/theory.md §4.1–4.3), symbolic in the parameters.

#include <ginac/ginac.h>

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/model.hpp"

namespace lagrange {

/// State layout and kinematics q̇ = K(q) v (docs/theory.md §2): the model's plain coordinates
/// first (q̇ = v), then each free body's r, R (9 entries) and ṙ, ω (body frame) (§4.4).
struct Kinematics {
  const Model* model = nullptr;
  std::vector<GiNaC::symbol> q, v, a;  ///< nq, nv, nv symbols
  std::vector<GiNaC::ex> qdot;         ///< nq expressions of (q, v, γ)
  std::vector<std::string> q_names, v_names;
  size_t plain = 0;              ///< leading coordinates with q̇ = v
  bool has_gamma = false;        ///< some free body uses the drift correction rate γ
  GiNaC::symbol gamma{"gamma"};  ///< SO(3) drift correction rate, a tape parameter
  /// K = ∂q̇/∂v by columns: for each v_k, the non-zeros (j, ∂q̇ⱼ/∂v_k).
  std::vector<std::vector<std::pair<size_t, GiNaC::ex>>> K;
  /// The same non-zeros by rows: for each q_j, the pairs (k, ∂q̇ⱼ/∂v_k).
  std::vector<std::vector<std::pair<size_t, GiNaC::ex>>> K_rows;
  /// What each state symbol is ('q', 'v' or 'a') and its index, so that the dependencies of an
  /// expression are found in one pass over it instead of one `has` per symbol.
  std::map<GiNaC::ex, std::pair<char, size_t>, GiNaC::ex_is_less> role;
};

/// The kinematics of a model: plain coordinates, then free bodies with
/// Ṙ = R(Ω + Ξ), Ξ = (γ/2)((RᵀR)⁻¹ − 1) (docs/theory.md §4.4).
Kinematics kinematics(const Model& model);

/// The equations of motion of a model in the form
///   M(q,t) a = h(q,v,t) + Q(q,v,t) − Gᵀλ,   C(q,t) = 0,   C̈ = G a + c,
/// with state (q, v), q̇ = qdot(q, v) (docs/theory.md §2), all symbolic in (t, q, v, u, u̇, ü, p).
struct Equations {
  const Model* model = nullptr;  ///< the model these were derived from (symbols live there)
  Kinematics kin;                ///< state layout, q̇ = K(q) v
  size_t nq = 0;                 ///< number of position coordinates
  size_t nv = 0;                 ///< number of velocities (size of M)
  size_t m = 0;                  ///< number of constraints

  GiNaC::ex T, U, L;         ///< kinetic, potential energy, L = T − U (λᵀC kept apart)
  GiNaC::matrix M;           ///< nv×nv mass matrix ∂²T/∂v∂vᵀ
  std::vector<GiNaC::ex> h;  ///< forcing from L: ∂L/∂q − (∂²L/∂v∂qᵀ) v − ∂²L/∂v∂t
  std::vector<GiNaC::ex> Q;     ///< non-conservative generalised forces (virtual work)
  std::vector<GiNaC::ex> qdot;  ///< kinematics q̇ = K(q) v (identity for plain coordinates)

  std::vector<GiNaC::ex> C;     ///< constraints C(q,t), m of them
  GiNaC::matrix G;              ///< m×nv constraint Jacobian ∂Ċ/∂v (= ∂C/∂q when q̇ = v)
  GiNaC::matrix Cq;             ///< m×nq ∂C/∂q, for the position projection
  std::vector<GiNaC::ex> Cdot;  ///< Ċ = Σ ∂C/∂qⱼ q̇ⱼ + ∂C/∂t
  std::vector<GiNaC::ex> c;     ///< C̈ − G a: dĊ/dt at a = 0

  /// Recursive formulation (docs/theory.md §4.9): M = 1 and h = the accelerations, written in
  /// the symbols of `definitions` (each defined by the inputs and earlier ones, in order).
  bool recursive = false;
  std::vector<std::pair<GiNaC::symbol, GiNaC::ex>> definitions;
  /// Recursive: velocity i's articulated-body pivot D = SᵀIᴬS (§4.9), in the inputs and
  /// `definitions`; M is positive definite exactly when every pivot is positive.
  std::vector<GiNaC::ex> pivots;

  std::vector<GiNaC::ex> outputs;          ///< named outputs: the model's, then per free body
  std::vector<std::string> output_names;   ///< its orthonormality error ‖RᵀR − 1‖_F
  std::vector<GiNaC::ex> reaction_scales;  ///< Model::reactions' scales, in order

  /// Left side of velocity i's equation of motion (Euler–Lagrange for plain coordinates,
  /// Newton–Euler for bodies): Σⱼ Mᵢⱼ aⱼ − hᵢ.
  GiNaC::ex euler_lagrange_lhs(size_t i) const;
  /// Tape input symbols in their fixed order: t, q, v, u, u̇, ü, p (then γ when has_gamma).
  std::vector<GiNaC::symbol> tape_inputs() const;
};

/// How derive() writes the equations of motion.
enum class Formulation {
  Lagrangian,  ///< M and h from the energies (docs/theory.md §4.1–§4.4): any model
  Recursive,   ///< a from the articulated-body algorithm on Model::tree (§4.9): O(N) in size
};

/// Why `model` cannot take Formulation::Recursive, or "" when it can: it needs a joint tree that
/// carries every body and coordinate, and no constraints, particles, kinetic energy or torques.
std::string recursive_unsuitable(const Model& model);

/// Derive the equations of motion of `model`: particles and point masses through point
/// Jacobians (M = Σ m JᵀJ, docs/theory.md §8), user energies through ∂²L/∂v∂vᵀ (§4.1), forces and
/// dampers by virtual work (§4.2), constraints twice differentiated (§4.3). Recursive: see
/// Formulation; std::invalid_argument with recursive_unsuitable()'s reason when it does not apply.
Equations derive(const Model& model, Formulation form = Formulation::Lagrangian);

/// True when T + U is a constant of motion of the derived model: no forces, dampers, torques or
/// inputs, no t in T, U or the constraints, U free of velocities and a written kinetic energy
/// quadratic in them (docs/theory.md §8.2). simulate() then checks the energy at every sample.
bool conserves_energy(const Equations& eq);

/// Symbolic accelerations a = M⁻¹(h + Q) for unconstrained systems with nv ≤ 4 (for tests),
/// normalised. Throws std::invalid_argument when constrained or nv > 4.
std::vector<GiNaC::ex> solve_accelerations(const Equations& eq);

/// The same for display, within a budget: std::nullopt when Cramer's numerators or denominator
/// would expand to more than `budget` terms, so that no printer does unbounded algebra.
std::optional<std::vector<GiNaC::ex>> solve_accelerations(const Equations& eq, size_t budget);

/// A canonical rational form with sin² + cos² = 1 applied (for display and for symbolic
/// equality tests: a and b are equal when simplify(a − b) is zero).
GiNaC::ex simplify(const GiNaC::ex& e);

}  // namespace lagrange
