#pragma once
// The optimal-control problem as a nonlinear program (docs/theory.md §10): Radau IIA collocation
// of the implicit DAE, variables and constraints laid out interval by interval, with bounds, a
// starting point, values and the exact sparse first derivatives.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/analysis.hpp"
#include "lagrange/optimal_control.hpp"
#include "optimize/point_functions.hpp"
#include "optimize/radau.hpp"

namespace lagrange::collocation {

/// Variables: [T when free], then per interval k < N the state X_{k,0…d−1} (x = (q, v)), the
/// multipliers Λ_{k,1…d} and the controls U_k, then X_{N,0}; X_{k,d} is X_{k+1,0}.
/// Constraints: per interval and collocation point j the DAE residual (nq + nv + m rows) and the
/// path constraints; then C = 0 and Ċ = 0 at t = 0 when the initial state is not all fixed.
class Transcription {
 public:
  Transcription(const Equations& eq, std::shared_ptr<const CompiledModel> cm, Dynamics& dyn,
                const OptimalControlSpec& spec, int intervals, int degree,
                const std::vector<double>& q0, const std::vector<double>& v0);

  size_t variables() const { return n_; }
  size_t constraints() const { return rows_; }
  void bounds(double* xl, double* xu, double* gl, double* gu) const;
  /// The starting point (docs/theory.md §10, "Initial guess"), made once: states interpolated
  /// linearly between the boundary states or simulated, controls at their guesses, multipliers
  /// from the forward dynamics there.
  const std::vector<double>& guess() const { return guess_; }

  double objective(const double* x);  ///< ±J, minimised
  void gradient(const double* x, double* grad);
  void constraint_values(const double* x, double* g);
  /// (row, column) of the Jacobian's structural non-zeros, each once.
  const std::vector<std::pair<size_t, size_t>>& jacobian_pattern() const { return nz_; }
  void jacobian(const double* x, double* values);
  /// What constraint `row` is and where, in words ("equation of motion of 'x_dot' at t = 0.25").
  std::string describe(size_t row, const double* x) const;

  // Reading a point of the NLP.
  int intervals() const { return N_; }
  const Radau& scheme() const { return rad_; }
  double horizon(const double* x) const { return free_T_ ? x[0] : T_; }
  double time(const double* x, int k, int j) const;
  const double* state(const double* x, int k, int j) const { return x + xi(k, j); }
  const double* multipliers(const double* x, int k, int j) const { return x + li(k, j); }
  const double* control(const double* x, int k) const { return x + ui(k); }
  bool maximize() const { return sign_ < 0; }
  const std::vector<size_t>& control_inputs() const { return controls_; }

 private:
  // Offsets of X_{k,j}, Λ_{k,j} (j ≥ 1), U_k.
  size_t xi(int k, int j) const;
  size_t li(int k, int j) const;
  size_t ui(int k) const;
  /// The tape inputs (t, q, v, u, u̇, ü, p) at a point with controls `u`.
  const std::vector<double>& load(double t, const double* x, const double* u);
  /// x'(τ_j)/h of interval k into qp_, and the residual's dynamics at (k, j) with the controls
  /// held: values into r (nq + nv + m).
  void residual(const double* x, int k, int j, double* r);
  std::vector<double> make_guess();
  /// Every Jacobian entry as emit(row, column, value), in a fixed order.
  template <class Emit>
  void walk_jacobian(const double* x, Emit&& emit);

  const Equations& eq_;
  std::shared_ptr<const CompiledModel> cm_;
  Dynamics& dyn_;
  const OptimalControlSpec& spec_;
  DynamicsJacobian jac_;
  PointFunctions fun_;  ///< L, Φ, then the path constraints
  Radau rad_;
  int N_, d_;
  size_t nq_, nv_, nx_, m_, nu_, np_;
  bool free_T_;
  double T_;
  double sign_;
  bool consistency_;               ///< C = 0, Ċ = 0 imposed at t = 0
  bool final_invariants_ = false;  ///< C = 0, Ċ = 0 at t = T: not imposed (nearly redundant)
  std::vector<size_t> controls_;
  std::vector<double> q0_, v0_;
  size_t n_ = 0, rows_ = 0, block_ = 0, first_ = 0, path_rows_ = 0;
  std::vector<std::pair<size_t, size_t>> nz_;
  std::vector<size_t> slot_;  ///< per emitted entry, its index in nz_
  std::vector<double> in_, out_, xp_, guess_;
};

}  // namespace lagrange::collocation
