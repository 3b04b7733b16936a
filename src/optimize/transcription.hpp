#pragma once
// The optimal-control problem as a nonlinear program (docs/theory.md §10): Radau IIA collocation
// of the implicit DAE, variables and constraints laid out interval by interval, with bounds, a
// starting point, values and the exact sparse first derivatives.

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/analysis.hpp"
#include "lagrange/optimal_control.hpp"
#include "lagrange/optimize.hpp"
#include "optimize/invariant_jacobian.hpp"
#include "optimize/point_functions.hpp"
#include "optimize/point_residual.hpp"
#include "optimize/radau.hpp"
#include "optimize/second_derivatives.hpp"

namespace lagrange::collocation {

/// The six entries (i ≤ j) of RᵀR − 1 that a free body's orthonormality invariant holds.
inline constexpr std::array<std::pair<size_t, size_t>, 6> kOrthonormalPairs{
    {{0, 0}, {0, 1}, {0, 2}, {1, 1}, {1, 2}, {2, 2}}};
/// (i, j) of the entries whose (M_ij − M_ji)/2 are vee(skew M)'s x, y and z.
inline constexpr std::array<std::pair<size_t, size_t>, 3> kSkewPairs{{{2, 1}, {0, 2}, {1, 0}}};

/// Variables: [T when free], then per interval k < N the state X_{k,0…d−1} (x = (q, v)), the
/// multipliers Λ_{k,1…d} and the controls U_k (a polynomial control: U_{k,1…d}), then X_{N,0};
/// X_{k,d} is X_{k+1,0}.
/// Constraints: per interval and collocation point j the DAE residual (nq + nv + m rows) and the
/// path constraints; then the invariants C = 0, Ċ = 0 at t = 0 that the fixed initial values do
/// not already imply; then x(T) − x(0) for the periodic components the invariants leave
/// independent; then U_{k+1,c} − U_{k,c} for each constant control. Final values that the
/// invariants imply (the dynamics keep them) are not imposed
/// but checked (implied_final_gaps).
/// Where a homotopy stage starts (docs/theory.md §10, "Homotopy"): the point `x` (an earlier
/// solve's, the same layout, owned by the caller; null: the problem's guess), the tracking weight,
/// and the DAE's compiled first and second derivatives when an earlier stage made them (the same
/// model and controls: only the objective differs).
struct StageStart {
  const std::vector<double>* x = nullptr;
  double track = 0.0;
  std::shared_ptr<const SecondDerivatives> dae_hessian;
  std::shared_ptr<const PointResidual> residual;  ///< an earlier stage's (the same DAE)
};

/// One NLP variable and its coefficient in a local column of a point's functions.
struct Term {
  size_t variable;
  double coefficient;
};

class Transcription {
 public:
  Transcription(const Equations& eq, std::shared_ptr<const CompiledModel> cm, Dynamics& dyn,
                const OptimalControlSpec& spec, int intervals, int degree,
                const std::vector<double>& q0, const std::vector<double>& v0,
                HessianChoice hessian = HessianChoice::Auto, const StageStart* stage = nullptr,
                Evaluation evaluation = Evaluation::Interpreter,
                const MachineCodeOptions& machine_code = {});

  size_t variables() const { return n_; }
  size_t constraints() const { return rows_; }
  void bounds(double* xl, double* xu, double* gl, double* gu) const;
  /// The starting point (docs/theory.md §10, "Initial guess"), made once: states interpolated
  /// linearly between the boundary states or simulated, controls at their guesses, multipliers
  /// from the forward dynamics there.
  /// A stage's start (StageStart::x) replaces it.
  const std::vector<double>& guess() const { return guess_; }
  /// The tracking term of a homotopy stage (docs/theory.md §10, "Homotopy"): `track` times the
  /// mean over the state nodes of Σ_i ((X_i − X̄_i)/s_i)², X̄ the starting point, s_i the largest
  /// |X̄_i| (at least 1); 0 without `track`. objective() includes it.
  double tracking(const double* x) const;

  double objective(const double* x);  ///< ±J, minimised
  void gradient(const double* x, double* grad);
  void constraint_values(const double* x, double* g);
  /// (row, column) of the Jacobian's structural non-zeros, each once.
  const std::vector<std::pair<size_t, size_t>>& jacobian_pattern() const { return nz_; }
  void jacobian(const double* x, double* values);
  /// The DAE's compiled second derivatives, for the next stage (null without the exact Hessian).
  std::shared_ptr<const SecondDerivatives> dae_hessian() const { return h_dae_; }
  /// The DAE's compiled rows and first derivatives, for the next stage.
  std::shared_ptr<const PointResidual> residual() const { return dae_; }
  /// Whether the exact Hessian of the Lagrangian is available (docs/theory.md §10, "Hessian").
  bool has_hessian() const { return hessian_ready_; }
  /// Why the exact Hessian was not made (empty when it was, or when it was not asked for).
  const std::string& hessian_note() const { return hessian_note_; }
  /// How the DAE's second derivatives run (SecondDerivatives::evaluation_note); empty without
  /// the exact Hessian.
  std::string hessian_evaluation() const { return h_dae_ ? h_dae_->evaluation_note() : ""; }
  std::string residual_evaluation() const { return dae_->evaluation_note(); }
  /// (row, column), row ≥ column, of the Hessian's structural non-zeros, each once.
  const std::vector<std::pair<size_t, size_t>>& hessian_pattern() const { return hnz_; }
  /// σ∇²J + Σ y_r ∇²g_r at x, in hessian_pattern() order (y: one multiplier per constraint).
  void hessian(const double* x, double sigma, const double* y, double* values);
  /// Ipopt's user scaling (nlp_scaling_method=user-scaling) from the problem's nominal
  /// magnitudes (docs/theory.md §10, "Scaling"):
  /// each variable by 1/its largest magnitude in the starting point and bounds (at least 1), each
  /// constraint and the objective down to a largest scaled gradient of 100 there.
  void scaling(double* x_scale, double* g_scale, double& f_scale);
  /// What constraint `row` is and where, in words ("equation of motion of 'x_dot' at t = 0.25").
  std::string describe(size_t row, const double* x) const;
  /// What variable `column` is and where ("'plane.wx' at t = 3.2", "control 'u' on interval 4").
  std::string describe_variable(size_t column, const double* x) const;
  /// A variable's quantity ("'plane.wx'", "control 'u'") and where it is ("at t = 3.2").
  struct VariableName {
    std::string quantity, where;
  };
  VariableName variable_name(size_t column, const double* x) const;
  /// A path constraint row's quantity ("path 'height'"), else "".
  std::string row_quantity(size_t row) const;
  /// A final value left out because the invariants imply it (docs/theory.md §10, "Constrained
  /// models"): its description, |x(T) − value|, and the same after x(T) is projected onto the
  /// invariants keeping the imposed final values (the collocation's drift removed).
  struct ImpliedGap {
    std::string what;
    double value = 0.0, gap = 0.0, projected = 0.0;
  };
  std::vector<ImpliedGap> implied_final_gaps(const double* x);

  // Reading a point of the NLP.
  int intervals() const { return N_; }
  const Radau& scheme() const { return rad_; }
  double horizon(const double* x) const { return free_T_ ? x[0] : T_; }
  double time(const double* x, int k, int j) const;
  const double* state(const double* x, int k, int j) const { return x + xi(k, j); }
  const double* multipliers(const double* x, int k, int j) const { return x + li(k, j); }
  /// The controls at τ_j of interval k, j = 0…d (a polynomial control at j = 0: its polynomial
  /// extrapolated to the interval's start), in a buffer the next call overwrites.
  const double* control(const double* x, int k, int j) const;
  /// Whether control c has a value at each collocation point (docs/theory.md §10, "Polynomial
  /// controls") rather than one per interval.
  bool polynomial(size_t c) const { return polynomial_[c]; }
  bool maximize() const { return sign_ < 0; }
  /// How many invariants (C_i, Ċ_i) are imposed at t = 0 and how many x(T) = x(0) rows.
  size_t start_invariant_rows() const { return start_rows_.size(); }
  size_t periodic_rows() const { return periodic_.size() + turning_.size(); }
  const std::vector<size_t>& control_inputs() const { return controls_; }
  /// The tape inputs (t, q, v, u, u̇, ü, p) at state x with controls `u` (the other inputs at
  /// their expressions), in a buffer the next call overwrites.
  const std::vector<double>& load(double t, const double* x, const double* u);

 private:
  // Offsets of X_{k,j}, Λ_{k,j} (j ≥ 1), and of control c at point j ≥ 1 of interval k (U_{k,j}
  // of a polynomial control, else U_k whatever j).
  size_t xi(int k, int j) const;
  size_t li(int k, int j) const;
  size_t ui(int k, int j, size_t c) const;
  /// How many values control c has per interval: d for a polynomial control, else 1.
  int control_points(size_t c) const { return polynomial_[c] ? d_ : 1; }
  /// The NLP variable of the point functions' column `column` ≥ 1 (q, v, the controls, λ) at
  /// collocation point (k, j ≥ 1); the terminal point is (N − 1, d).
  size_t point_variable(size_t column, int k, int j) const;
  /// The point functions at collocation point (k, j ≥ 1) into out_, at the tape inputs load()
  /// last made for that point (eval_residual's).
  void eval_point(const double* x, int k, int j);
  /// x'(τ_j) of interval k, (1/h) Σ_l D_jl X_{k,l}, into xp_.
  void collocation_derivative(const double* x, int k, int j);
  /// xp_, and ρ with its derivatives (PointResidual) at (k, j) into rout_; at a kink, the
  /// derivatives at the state moved off it (docs/theory.md §10, "Kinks").
  void eval_residual(const double* x, int k, int j);
  /// Every collocation point's x', ρ with its derivatives and the point functions with theirs
  /// at the NLP's variables x, computed once per x: Ipopt asks for the objective, the
  /// constraints and their derivatives at the same point, and each reads these.
  void evaluate_points(const double* x);
  /// At point p = k d + j − 1 of the x evaluate_points last had: x' (nx), ρ and its derivatives
  /// (rout_'s layout), the point functions and their derivatives (out_'s layout).
  const double* point_xp(size_t p) const { return xp_at_.data() + p * nx_; }
  const double* point_rho(size_t p) const { return rho_at_.data() + p * dae_->num_outputs(); }
  const double* point_fun(size_t p) const { return fun_at_.data() + p * fun_.num_outputs(); }
  /// Calls f(variable, coefficient) for each NLP variable of the DAE's local column `col` (q, v,
  /// the controls, a = v', λ) at point (k, j): a reaches the interval's states through the
  /// collocation derivative, and T (when free) through x' = (1/h) Σ D X with h = T/N
  /// (docs/theory.md §10, "Hessian"), with x' at the point in `xp`.
  template <class F>
  void for_each_residual_term(const double* x, const double* xp, int k, int j, size_t col,
                              F&& f) const {
    if (col < nx_) return f(xi(k, j) + col, 1.0);
    if (col < nx_ + nu_) return f(ui(k, j, col - nx_), 1.0);
    if (col < nx_ + nu_ + nv_) {
      const double T = horizon(x), h = T / N_;
      const size_t i = col - nx_ - nu_;
      for (int l = 0; l <= d_; ++l) f(xi(k, l) + nq_ + i, rad_.derivative(j, l) / h);
      if (free_T_) f(size_t{0}, -xp[nq_ + i] / T);  // ∂x'/∂T = −x'/T
      return;
    }
    f(li(k, j) + col - nx_ - nu_ - nv_, 1.0);
  }
  /// The same as a list in `t`, with x' in xp_.
  void residual_terms(const double* x, int k, int j, size_t col, std::vector<Term>& t) const;
  std::vector<double> make_guess();
  /// Calls f(offset of X) for each state node X_{k,j} (k < N, j < d) and X_{N,0}.
  template <class F>
  void for_each_node(F&& f) const {
    for (int k = 0; k < N_; ++k)
      for (int j = 0; j < d_; ++j) f(xi(k, j));
    f(xi(N_, 0));
  }
  /// The guessed state at time t: the guessed paths (with their time derivatives) where written,
  /// else linear between `start` and `end`; with constraints, projected onto C = 0, Ċ = 0 keeping
  /// the components flagged in `keep`.
  std::vector<double> guessed_state(double t, const std::vector<double>& start,
                                    const std::vector<double>& end, const std::vector<bool>& keep);
  /// The boundary state at t = 0 (`end` false) or T: the model's start with the fixed boundary
  /// values written in, projected onto the invariants keeping them.
  std::vector<double> boundary_state(bool end);
  /// Rows of the invariants' gradients ∂(C, Ċ, RᵀR)/∂(q, v) at (t, X) as emit(invariant, column,
  /// value), numbered as invariants() counts them; with constraints the last tape evaluation is
  /// dyn_'s.
  template <class Emit>
  void invariant_gradients(double t, const double* X, Emit&& emit);
  /// The invariants: C (m), Ċ (m), then RᵀR = 1 of each free body (6 entries each).
  size_t invariants() const { return 2 * m_ + 6 * rotations_.size(); }
  /// Entry `which` (from 0, body by body) of the free bodies' RᵀR − 1 at the state X.
  double orthonormality(const double* X, size_t which) const;
  /// Component w of vee(skew(R(0)ᵀR(T))) for the body whose R11 is q[base], from the states at
  /// t = 0 and T; zero when the body has turned back.
  double turning(const double* X0, const double* XT, size_t base, size_t w) const;
  /// Its gradient: on_start(column, value) for R(0)'s entries, on_end for R(T)'s.
  template <class EmitA, class EmitB>
  void turning_gradient(const double* X0, const double* XT, size_t base, size_t w, EmitA&& on_start,
                        EmitB&& on_end) const;
  /// Compiles the second derivatives of the DAE, the point functions and the invariants, and
  /// finds the Hessian's pattern (docs/theory.md §10, "Hessian").
  void prepare_hessian(HessianChoice choice, std::shared_ptr<const SecondDerivatives> dae,
                       Evaluation evaluation, const MachineCodeOptions& machine_code);
  /// Every Hessian entry as emit(row, column, value), row ≥ column, in a fixed order.
  template <class Emit>
  void walk_hessian(const double* x, double sigma, const double* y, Emit&& emit);
  /// Splits the boundary values into those imposed and those the invariants imply, and chooses
  /// the invariants imposed at t = 0 (docs/theory.md §10, "Constrained models").
  void choose_boundary_rows();
  /// Every Jacobian entry as emit(row, column, value), in a fixed order.
  template <class Emit>
  void walk_jacobian(const double* x, Emit&& emit);

  const Equations& eq_;
  std::shared_ptr<const CompiledModel> cm_;
  Dynamics& dyn_;
  const OptimalControlSpec& spec_;
  PointFunctions fun_;                        ///< L, Φ, then the path constraints
  std::shared_ptr<const PointResidual> dae_;  ///< the DAE's rows at a point and derivatives
  InvariantJacobian invariant_jac_;  ///< ∂(C, Ċ)/∂(q, v) for the invariants imposed at t = 0
  Radau rad_;
  int N_, d_;
  size_t nq_, nv_, nx_, m_, nu_, np_;
  bool free_T_;
  double T_;
  double sign_;
  /// Invariants imposed at t = 0 (i < m: C_i, i < 2m: Ċ_{i−m}, else the free bodies' RᵀR = 1).
  std::vector<size_t> start_rows_;
  std::vector<size_t> rotations_;       ///< per free body, the index of R11 in q (R row-major)
  std::vector<BoundaryValue> final_;    ///< final values imposed as bounds
  std::vector<BoundaryValue> implied_;  ///< final values the invariants imply, checked only
  std::vector<size_t> periodic_;        ///< state components with x(T) = x(0) imposed
  /// Periodic orientations: (R11's index in q, w) for each row vee(skew(R(0)ᵀR(T)))_w = 0, the
  /// last rows of the NLP.
  std::vector<std::pair<size_t, size_t>> turning_;
  std::vector<size_t> constant_;  ///< controls with one value over the horizon
  PointFunctions paths_;          ///< the guessed paths and their time derivatives
  std::vector<size_t> controls_;
  std::vector<bool> polynomial_;     ///< per control: a value at each collocation point
  std::vector<size_t> u_offset_;     ///< per control: its first variable after an interval's Λ
  std::vector<double> start_basis_;  ///< ℓ̃_j(0): a polynomial control at the interval's start
  mutable std::vector<double> u_;    ///< control()'s buffer
  std::vector<double> q0_, v0_;
  size_t n_ = 0, rows_ = 0, block_ = 0, first_ = 0, path_rows_ = 0;
  std::vector<std::pair<size_t, size_t>> nz_;
  std::vector<size_t> slot_;  ///< per emitted entry, its index in nz_
  std::vector<double> in_, out_, xp_, guess_;
  std::vector<double> rin_, rout_;      ///< eval_residual's inputs and outputs
  std::vector<double> sig_, sig_work_;  ///< load()'s other inputs and their tape's scratch
  std::vector<double> x_at_, xp_at_, rho_at_, fun_at_;  ///< evaluate_points' x and results
  double track_ = 0.0;               ///< the tracking term's weight over the node count
  std::vector<double> track_scale_;  ///< per state component, 1/s_i²
  // The Hessian: ∂² of Σ μ·(DAE residual) over (q, v, u, a, λ), of the weighted point
  // functions over (q, v, u), of the weighted invariants over (q, v).
  std::shared_ptr<const SecondDerivatives> h_dae_;
  SecondDerivatives h_point_, h_invariants_;
  bool hessian_ready_ = false;
  std::string hessian_note_;
  std::vector<std::pair<size_t, size_t>> hnz_;
  std::vector<size_t> hslot_;
  std::vector<double> hin_, hout_;
};

}  // namespace lagrange::collocation
