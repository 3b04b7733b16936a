#pragma once
// Numeric forward dynamics: one KKT path for constrained and unconstrained systems.

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/machine_code.hpp"

namespace lagrange {

namespace dynamics {
class SparseRangeSpace;
struct NativeTapes;
struct ProjectionWorkspace;
}  // namespace dynamics

/// What evaluates a Dynamics' tapes (docs/theory.md §8, machine code). Both give the same
/// numbers bit for bit; machine code is faster per call but costs a compiler run when not cached.
enum class Evaluation {
  Interpreter,  ///< the tape interpreter
  MachineCode,  ///< machine code, compiled at once when not cached; the interpreter if that fails
  Background,   ///< machine code from the cache, else the interpreter until a compiler run in the
                ///< background finishes (tapes under kBackgroundMinInstructions are not compiled)
  /// Machine code reading the tapes' constants from memory (Tape::to_shared_c): one library,
  /// compiled at once when not cached, serves every parameter value whose specialised tapes
  /// fold alike, so a new value costs no compiler run (parameter studies); the interpreter if
  /// it cannot be had.
  SharedMachineCode,
};

/// Result of projecting a state onto the constraint manifold.
struct ProjectionResult {
  double position_change = 0.0;  ///< ‖Δq‖₂
  double velocity_change = 0.0;  ///< ‖Δv‖₂
  double residual = 0.0;         ///< max |C| after projection
  double rate_residual = 0.0;    ///< max |Ċ| after projection
  int iterations = 0;
  bool converged = false;  ///< max |C| reached the tolerance
  /// Rounding floors of C and Ċ at the result (a few ulps of their terms |∂C/∂q||q|, |G||v|):
  /// residuals below them are as consistent as floating point allows.
  double floor = 0.0, rate_floor = 0.0;
};

/// Replaces each free body's R in q by the nearest rotation (polar factor U Vᵀ of R = U Σ Vᵀ,
/// docs/theory.md §4.4) where ‖RᵀR − 1‖_F exceeds `tol` (so q changed when the result exceeds
/// tol); returns the largest ‖RᵀR − 1‖_F found before the change, 0 without free bodies.
double orthonormalize_rotations(const CompiledModel& model, double* q, double tol);

/// Mutable workspace over a CompiledModel: tapes specialised to the current parameter values
/// and all scratch memory, so that forward() never allocates. Not thread-safe; make one per thread.
class Dynamics {
 public:
  Dynamics(std::shared_ptr<const CompiledModel> model, const std::vector<double>& parameters);
  ~Dynamics();
  Dynamics(Dynamics&&) noexcept;
  Dynamics& operator=(Dynamics&&) noexcept;

  const CompiledModel& model() const { return *model_; }
  const std::vector<double>& parameters() const { return params_; }
  /// Change parameter values: re-specialises the tapes (no new derivation).
  void set_parameters(const std::vector<double>& values);
  /// Choose what evaluates the tapes (Interpreter by default); applies to the current and later
  /// parameter values. Never throws: when machine code cannot be had, evaluation_note() says why.
  void set_evaluation(Evaluation mode, const MachineCodeOptions& options = {});
  /// True when calls run on machine code now (in Background mode it may become true later).
  bool uses_machine_code() const;
  /// One line on what evaluates the tapes: "machine code (compiled in 0.41 s)", "interpreter", or
  /// "interpreter (machine code failed: …)".
  std::string evaluation_note() const;
  /// Why machine code that was asked for could not be had (empty when it could, or when it is
  /// still compiling, or was not tried).
  std::string machine_code_error() const;
  /// Smallest dynamics tape that Background mode compiles: smaller tapes interpret in well under a
  /// microsecond, less than a compiler run could ever win back in a typical simulation.
  static constexpr size_t kBackgroundMinInstructions = 400;

  /// Every evaluation from now on takes input `index` (into model().input_names) as `value`
  /// with u̇ = ü = 0 instead of its declared expression: a caller-set input held between calls.
  void hold_input(size_t index, double value);
  /// A caller's law for some inputs, evaluated at every evaluation: law(t, q, v, u) writes
  /// u[j] for input indices[j] (u̇ = ü = 0 as for held inputs); an empty law removes it.
  using InputLaw = std::function<void(double t, const double* q, const double* v, double* u)>;
  void set_input_law(std::vector<size_t> indices, InputLaw law);
  /// The inputs follow their declared expressions again (no held values, no law).
  void release_inputs();

  /// Baumgarte rate α (docs/theory.md §4.3): constraint errors decay like exp(−α t).
  void set_baumgarte(double alpha) { alpha_ = alpha; }
  double baumgarte() const { return alpha_; }

  /// Forward dynamics at (t, q, v): q̇, accelerations a and multipliers λ (m of them) from
  ///   [M Gᵀ; G 0][a; λ] = [h + Q; −c − 2αĊ − α²C]   (docs/theory.md §4.3).
  /// Throws SimulationError naming t and the state when M or G M⁻¹Gᵀ is singular.
  void forward(double t, const double* q, const double* v, double* qdot, double* a, double* lambda);

  /// Residual of the index-1 DAE in (q, v, λ) used with IDA (docs/theory.md §4.3):
  ///   r_q = q' − q̇(q, v),  r_v = M v' + Gᵀλ − (h + Q),  r_λ = G v' + c + 2αĊ + α²C.
  void dae_residual(double t, const double* q, const double* v, const double* qp, const double* vp,
                    const double* lambda, double* r);

  /// T, U and the model's outputs at (t, q, v), written to `out` (2 + outputs values).
  void observe(double t, const double* q, const double* v, double* out);
  /// Constraint values C and Ċ at (t, q, v).
  void constraints(double t, const double* q, const double* v, double* C, double* Cdot);
  /// C and Ċ at the state of the last forward() or constraints() call, without a new
  /// evaluation (the dynamics tape computes them alongside M and h).
  void last_constraints(double* C, double* Cdot) const;

  /// Project (q, v) onto C = 0 (damped Gauss–Newton, least-squares change of the non-fixed
  /// coordinates), then Ċ = 0 (least-squares change of the non-fixed velocities). When max |C|
  /// cannot be brought to `tol`, stops at the state of least ‖C‖₂ found, with converged = false.
  ProjectionResult try_project(double t, double* q, double* v, const std::vector<bool>& fixed,
                               double tol = 1e-12, int max_iterations = 50);
  /// As try_project, but throws SimulationError when it does not converge.
  ProjectionResult project(double t, double* q, double* v, const std::vector<bool>& fixed,
                           double tol = 1e-12, int max_iterations = 50);

  /// The dynamics tape input vector after the last evaluation (t, q, v, u, p).
  const std::vector<double>& last_inputs() const { return in_; }

 private:
  void load_inputs(double t, const double* q, const double* v);
  /// Evaluate tape `slot` (dynamics::TapeSlot) of the current inputs into `out`.
  void run(size_t slot, const Tape& tape, double* out);
  void eval_dynamics(double t, const double* q, const double* v);
  void assemble_M();
  void assemble_G();
  void solve_full_kkt(double t);
  [[noreturn]] void fail_singular(double t, const std::string& what) const;
  [[noreturn]] void fail_redundant(double t) const;

  std::shared_ptr<const CompiledModel> model_;
  std::vector<double> params_;
  std::vector<std::pair<size_t, double>> held_;  // inputs set by the caller: index, value
  std::vector<size_t> law_inputs_;               // inputs the law sets
  std::vector<double> law_values_;
  InputLaw law_;
  double alpha_ = 0.0;
  Tape dyn_, obs_, sig_;
  std::vector<double> in_, out_, obs_out_, sig_out_, work_;
  Eigen::MatrixXd M_, G_, Y_, S_;
  Eigen::VectorXd rhs_, a_, gamma_, lambda_;
  Eigen::LLT<Eigen::MatrixXd> llt_M_, llt_S_;
  Eigen::MatrixXd K_;  // full KKT matrix, used only when M is singular
  Eigen::VectorXd kkt_rhs_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_K_;
  std::unique_ptr<dynamics::SparseRangeSpace> sparse_;         // diagonal M with many constraints
  std::unique_ptr<dynamics::NativeTapes> native_;              // machine code, when chosen
  std::unique_ptr<dynamics::ProjectionWorkspace> projection_;  // set up by the first projection
  /// Build or start building machine code for the current tapes (after set_parameters).
  void refresh_machine_code();
};

}  // namespace lagrange
