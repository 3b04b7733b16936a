#pragma once
// What is computed from the dynamics rather than by integrating it (docs/theory.md §5): exact
// Jacobians, linearisation on the constraint manifold with modes, and trim (equilibria).

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <complex>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/integrator.hpp"
#include "lagrange/tape.hpp"

namespace lagrange {

/// A numerical failure of an analysis (singular Jacobian, Newton stalled): exit code 3.
class AnalysisError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// The dynamics have no derivative at the state (|x| at x = 0, max or min at a tie).
class NotDifferentiable : public AnalysisError {
 public:
  using AnalysisError::AnalysisError;
};

/// Derivatives at one state (t, q, v): values and exact first derivatives of the accelerations,
/// the kinematics, the constraints and the model's outputs, with respect to q, v and the named
/// inputs w (columns of the *_w blocks in DynamicsJacobian::input_names() order).
struct StateJacobian {
  Eigen::VectorXd qdot, a, lambda;  ///< nq, nv, m
  /// ∂q̇/∂q (nq×nq), ∂q̇/∂v (nq×nv): for a free body Ṙ = R(Ω + Ξ), drift correction included.
  Eigen::MatrixXd qdot_q, qdot_v;
  Eigen::MatrixXd a_q, a_v, a_w;   ///< ∂a/∂q (nv×nq), ∂a/∂v (nv×nv), ∂a/∂w (nv×nw)
  Eigen::MatrixXd G, C_q, Cdot_q;  ///< m×nv ∂Ċ/∂v, m×nq ∂C/∂q, m×nq ∂Ċ/∂q
  Eigen::VectorXd y;               ///< the model's outputs (Equations::outputs)
  Eigen::MatrixXd y_q, y_v, y_w;   ///< their derivatives
};

/// The dynamics in implicit form at one state, Φ(q, v, a, λ) = (M a + Gᵀλ − f, G a − γ) = 0,
/// with its sparse Jacobians (docs/theory.md §5.1, "Implicit form"): ∂(a, λ)/∂x = −K⁻¹ Phi_x.
/// For implicit integrators and Newton solvers that factorise K themselves.
struct ImplicitJacobian {
  Eigen::VectorXd qdot, a, lambda;  ///< nq, nv, m (from Dynamics::forward)
  Eigen::SparseMatrix<double> K;    ///< ∂Φ/∂(a, λ) = [M Gᵀ; G 0], (nv + m)²
  Eigen::SparseMatrix<double> Phi_x;  ///< ∂Φ/∂(q, v, w), a and λ held: (nv + m) × (nq + nv + nw)
  Eigen::SparseMatrix<double> qdot_x;  ///< ∂q̇/∂(q, v): nq × (nq + nv)
};

namespace analysis_detail {
class KktLayout;
}

/// The dynamics tape's outputs (M, h + Q, q̇, G, c, Ċ, C) and named model outputs with their exact
/// derivatives with respect to q, v and named inputs (model `inputs:` or parameters), compiled
/// onto one tape that keeps only the structural non-zeros (docs/theory.md §5.1). Immutable.
class DynamicsJacobian {
 public:
  /// Differentiate `eq` (compiled as `cm`) symbolically. `inputs` names model inputs or
  /// parameters, `outputs` model outputs (CompiledModel::output_names) to differentiate too;
  /// std::invalid_argument for an unknown or repeated name (saying what is known) and for the
  /// recursive formulation (derive with Formulation::Lagrangian).
  DynamicsJacobian(const Equations& eq, std::shared_ptr<const CompiledModel> cm,
                   const std::vector<std::string>& inputs = {},
                   const std::vector<std::string>& outputs = {});

  const CompiledModel& model() const { return *cm_; }
  const std::vector<std::string>& input_names() const { return input_names_; }
  const std::vector<std::string>& output_names() const { return output_names_; }
  /// Structural non-zeros of the derivatives (the sparsity the tape keeps).
  size_t nonzeros() const { return pattern_.size(); }
  const Tape& tape() const { return tape_; }
  /// The tape's outputs: value_count() values (the dynamics tape's up to ∂C/∂q, then the model
  /// outputs), then one derivative per pattern() entry (value index, column).
  size_t value_count() const { return values_; }
  const std::vector<std::pair<size_t, size_t>>& pattern() const { return pattern_; }

  /// Values and derivatives at (t, q, v) with `dyn`'s parameter values and Baumgarte rate α.
  /// The accelerations come from dyn.forward (the one KKT path); their derivatives from the
  /// differentiated KKT system, one more factorisation of [M Gᵀ; G 0] (docs/theory.md §5.1).
  /// Throws AnalysisError when that matrix is singular. A derivative the tape gives as 0/0 is
  /// its limit (|v|·v at v = 0); NotDifferentiable where that depends on the direction.
  StateJacobian evaluate(Dynamics& dyn, double t, const double* q, const double* v) const;

  /// The implicit form's sparse Jacobians at (t, q, v): one forward call, one evaluation of the
  /// tape and one pass over its outputs, no factorisation (docs/theory.md §5.1).
  ImplicitJacobian implicit(Dynamics& dyn, double t, const double* q, const double* v) const;
  /// The same at given accelerations a (nv) and multipliers λ (m) instead of the forward call's:
  /// the Jacobians of the residual Φ(q, v, a, λ) anywhere (dae_jacobian). One evaluation of the
  /// dynamics tape (for its inputs), one of this tape, no KKT solve.
  ImplicitJacobian implicit(Dynamics& dyn, double t, const double* q, const double* v,
                            const double* a, const double* lambda) const;

 private:
  /// evaluate() with the tape's non-finite derivatives left as they are.
  StateJacobian evaluate_here(Dynamics& dyn, double t, const double* q, const double* v) const;

  std::shared_ptr<const CompiledModel> cm_;
  std::vector<std::string> input_names_, output_names_;
  std::vector<size_t> columns_;  ///< tape input index of each column: q, v, then the inputs
  size_t values_ = 0;            ///< leading tape outputs that are values, not derivatives
  size_t outputs_ = 0;           ///< model outputs among the values (after the dynamics')
  std::vector<std::pair<size_t, size_t>> pattern_;  ///< (value index, column) per derivative
  Tape tape_;
  std::shared_ptr<const analysis_detail::KktLayout> layout_;
  bool range_space_ = false;  ///< M block diagonal: the KKT solves in range-space form

  /// Dynamics::forward into J's qdot, a, lambda (sized here), then the tape at its inputs.
  std::vector<double> values_at(Dynamics& dyn, double t, const double* q, const double* v,
                                ImplicitJacobian& J) const;
};

/// The exact Jacobian of y' = f(y), y = (q, v): [∂q̇/∂q ∂q̇/∂v; ∂a/∂q ∂a/∂v] from `jac` (for a
/// free body's nine entries of R as the integrator sees them), for cvode:jacobian
/// (OdeProblem::jacobian), on the pattern of the entries non-zero at y0 or at two states nearby
/// (docs/theory.md §5.6). Refers to `jac` and `dyn`, which must outlive it.
OdeJacobian ode_jacobian(const DynamicsJacobian& jac, Dynamics& dyn, double t0,
                         const std::vector<double>& y0);

/// The exact Newton matrix ∂F/∂y + c_j ∂F/∂y' of the index-1 DAE that `ida` integrates,
/// y = (q, v, λ), F = Dynamics::dae_residual, from `jac`'s implicit form at the state's own
/// v' and λ, sparse (docs/theory.md §5.6, "The DAE's Newton matrix"), for ida:jacobian
/// (DaeProblem::jacobian); its pattern is fixed by `jac`, taken at (t0, y0) (y0: q and v at
/// least). Refers to `jac` and `dyn`, which must outlive it.
DaeJacobian dae_jacobian(const DynamicsJacobian& jac, Dynamics& dyn, double t0,
                         const std::vector<double>& y0);

/// Tangent coordinates of the positions (docs/theory.md §5.2): nv of them, one per velocity:
/// plain coordinates themselves, a free body's r and a local rotation vector δθ with
/// R = R₀ exp([δθ]×). `T` (nq×nv) maps them to q to first order: δq = T δx.
struct TangentChart {
  std::vector<std::string> names;  ///< nv: plain names, `<body>.x`…, `<body>.dtheta_x`…
  Eigen::MatrixXd T;               ///< nq×nv
  /// ∂ẋ/∂x at velocity v: zero except −½[ω]× per free body (δθ̇ = ω + ½ δθ×ω + O(δθ²)).
  Eigen::MatrixXd rate_x;
};

/// The chart at q, v.
TangentChart tangent_chart(const CompiledModel& cm, const double* q, const double* v);

/// q ⊕ δx: plain coordinates and r added, R ← R exp([δθ]×) (Rodrigues).
void retract(const CompiledModel& cm, const double* dx, double* q);

/// A linear model δż = A δz + B δw, δy = C δz + D δw about an operating point (continuous time,
/// or with `dt` > 0 the zero-order-hold discretisation δz⁺ = A δz + B δw).
struct LinearModel {
  std::vector<std::string> state_names;   ///< independent positions, then their rates
  std::vector<std::string> input_names;   ///< columns of B and D
  std::vector<std::string> output_names;  ///< rows of C and D
  Eigen::MatrixXd A, B, C, D;
  double dt = 0.0;  ///< sampling time of a discrete model, 0 when continuous
  /// The full tangent state (δx, v) (2nv, TangentChart names then velocity names) of each reduced
  /// state: W, with S W = 1 for the selection S of the independent ones (docs/theory.md §5.3).
  std::vector<std::string> full_state_names;
  Eigen::MatrixXd basis;
  /// Constrained models: the coordinates (tangent names) expressed through the independent ones.
  std::vector<std::string> dependent;
  double equilibrium_residual = 0.0;  ///< max |q̇|, |a| at the operating point (0 at equilibrium)
};

/// Linearise at (t, q, v) (a consistent state), on the constraint manifold {C = 0, Ċ = 0} for
/// constrained models (docs/theory.md §5.3). `outputs` names coordinates, tangent coordinates,
/// velocities or model outputs; empty: the reduced state itself (C = 1, D = 0).
/// std::invalid_argument for an unknown output name.
LinearModel linearize(const DynamicsJacobian& jac, Dynamics& dyn, double t, const double* q,
                      const double* v, const std::vector<std::string>& outputs = {});

/// Zero-order-hold discretisation: exp([A B; 0 0] dt) = [A_d B_d; 0 1] (docs/theory.md §5.4).
/// std::invalid_argument unless dt is positive and finite; AnalysisError naming dt when the
/// exponential overflows a double (a model that grows by more than 10³⁰⁸ over one step).
LinearModel discretize(const LinearModel& continuous, double dt);

/// One eigenvalue of A (one per complex-conjugate pair, Im ≥ 0) and what it means physically.
struct Mode {
  std::complex<double> eigenvalue;
  double frequency_hz = 0.0;   ///< |λ|/2π (undamped natural frequency)
  double damping = 0.0;        ///< ζ = −Re λ / |λ| (1 for a real negative eigenvalue)
  double time_constant = 0.0;  ///< −1/Re λ; infinite when Re λ = 0, negative when unstable
  /// Largest components of the eigenvector in the full tangent state, by name, normalised so
  /// that the largest has magnitude 1: (name, magnitude, phase in degrees).
  struct Component {
    std::string name;
    double magnitude, phase_deg;
  };
  std::vector<Component> shape;
};

/// Modes of a continuous linear model, sorted by |λ| then Im λ; `components` per mode shape.
std::vector<Mode> modes(const LinearModel& lin, size_t components = 4);

/// Options of trim().
struct TrimOptions {
  /// Per tangent coordinate (nv): varied by Newton. Empty: all, except the coordinates that
  /// move at a held rate (`steady`), whose value is only the phase of the steady motion.
  std::vector<bool> free;
  /// Per velocity (nv): held at its value in v0, a steady state (docs/theory.md §5.5); the
  /// velocities not held are 0. Empty: none held, an equilibrium. Plain coordinates only.
  std::vector<bool> steady;
  /// Per velocity (nv): a held rate that Newton varies instead (its v0 value is the start).
  std::vector<bool> free_rates;
  /// Per DynamicsJacobian input (model inputs or parameters, in input_names() order): varied
  /// by trim too, e.g. joint torques that hold a robot still (docs/theory.md §5.5, "Free
  /// inputs"). Empty: none. On success `dyn` keeps the values found (inputs held, parameters
  /// set); on failure the start values are restored.
  std::vector<bool> free_inputs;
  /// On max |a|, raised to the rounding floor of the accelerations where that is larger
  /// (docs/theory.md §5.5, "Tolerance"); also on max |Ċ| of held rates.
  double tol = 1e-10;
  int max_iterations = 100;  ///< Levenberg–Marquardt iterations
  /// When Levenberg–Marquardt fails (not for varied rates): pseudo-transient continuation from the
  /// start, at most this many steps (0: none), first pseudo-time step pseudo_step
  /// (docs/theory.md §5.5).
  int max_pseudo_steps = 400;
  double pseudo_step = 1e-2;
};

/// Result of trim(): the equilibrium or steady state and how it was found.
struct TrimResult {
  std::vector<double> q, v;    ///< v: the held rates, 0 elsewhere
  std::vector<double> inputs;  ///< the free inputs' values (TrimOptions::free_inputs order)
  double residual = 0.0;       ///< max |a| at (q, v)
  double tolerance = 0.0;      ///< what max |a| was held to: max(tol, the rounding floor)
  /// Empty, or why the equilibrium is one of a family (the Jacobian singular there, naming a
  /// coordinate the accelerations do not depend on).
  std::string not_isolated;
  /// max |ȧ| = max |∂a/∂q q̇| along the steady motion: 0 when the moving coordinates do not
  /// enter the accelerations (cyclic), else the state is only quasi-steady. 0 at equilibrium.
  double drift = 0.0;
  int iterations = 0;  ///< Levenberg–Marquardt's, or the pseudo-transient steps when it took them
  /// Found by pseudo-transient continuation after Levenberg–Marquardt failed.
  bool pseudo_transient = false;
};

/// An equilibrium (v = 0, a = 0) from q0 by Levenberg–Marquardt on ½‖a‖² with the exact
/// Jacobian ∂a/∂x (Newton's step whenever it decreases ‖a‖), constrained models kept on C = 0
/// by projection after each step (docs/theory.md §5.5). Throws AnalysisError saying why and
/// where it stopped.
TrimResult trim(const DynamicsJacobian& jac, Dynamics& dyn, double t, const std::vector<double>& q0,
                const TrimOptions& options = {});

/// A steady state: the rates options.steady held at their values in v0 (or varied, with
/// options.free_rates), the other velocities 0, a(q, v) = 0 (docs/theory.md §5.5). As trim()
/// above; std::invalid_argument for held rates of a free body or flags of the wrong size.
TrimResult trim(const DynamicsJacobian& jac, Dynamics& dyn, double t, const std::vector<double>& q0,
                const std::vector<double>& v0, const TrimOptions& options);

}  // namespace lagrange
