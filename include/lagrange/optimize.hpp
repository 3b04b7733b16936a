#pragma once
// Optimal control by direct collocation (docs/theory.md §10): the model file's
// `optimal_control:` problem transcribed with Radau IIA on the implicit DAE and solved by Ipopt.

#include <atomic>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "lagrange/compiled_model.hpp"
#include "lagrange/dynamics.hpp"
#include "lagrange/energy_balance.hpp"
#include "lagrange/equations.hpp"
#include "lagrange/optimal_control.hpp"
#include "lagrange/simulation.hpp"

namespace lagrange {

/// What Ipopt gets for the Hessian of the Lagrangian (docs/theory.md §10, "Hessian"): the exact
/// one (a fixed horizon), its limited-memory approximation, or the exact one unless the model's
/// equations exceed kHessianTerms distinct terms, beyond which the symbolic second derivatives
/// cost more set-up than they save (a 7-joint spatial arm).
enum class HessianChoice { Auto, Exact, LimitedMemory };
constexpr size_t kHessianTerms = 2000;

/// How optimize() transcribes and solves; unset sizes keep the problem's own.
struct OptimizeOptions {
  int intervals = 0;  ///< collocation intervals N (0: the problem's)
  int degree = 0;     ///< Radau IIA points per interval, 1 to 5 (0: the problem's)
  /// Ipopt options by name, as text: integers, numbers and words are told apart by their form.
  std::vector<std::pair<std::string, std::string>> ipopt;
  bool verbose = false;  ///< Ipopt's iteration log on stdout
  HessianChoice hessian = HessianChoice::Auto;
  /// How the exact Hessian's compiled second derivatives run (docs/theory.md §8): Background
  /// interprets them until machine code from the cache or a compiler run beside the solve is
  /// ready (the same bits, so the iterates do not change); MachineCode compiles before the solve.
  Evaluation evaluation = Evaluation::Background;
  MachineCodeOptions machine_code;
  /// Set asynchronously (Ctrl-C) to stop Ipopt after its current iteration: the result is then
  /// the last iterate, not optimal, its trajectory's status Interrupted.
  const std::atomic<bool>* interrupt = nullptr;
};

/// A homotopy stage as it ended (OptimalControlSpec::stages).
struct StageResult {
  std::string name;
  bool optimal = false;
  std::string status;  ///< Ipopt's status in words
  int iterations = 0;
  double objective = 0.0;  ///< the stage's objective, in its own sign, without the tracking term
  double tracking = 0.0;   ///< the tracking term's value (0 without `track`)
  double seconds = 0.0;    ///< set-up and solve
};

/// What optimize() found.
struct OptimizeResult {
  bool optimal = false;    ///< Ipopt converged to a (locally) optimal point
  std::string status;      ///< Ipopt's status in words
  double objective = 0.0;  ///< J at the result, in the problem's own sign (maximised: J itself)
  double horizon = 0.0;    ///< T
  /// Largest violation of a constraint (dynamics, path, consistency) and which one and where.
  double violation = 0.0;
  std::string worst_constraint;
  int iterations = 0;
  double setup_seconds = 0.0, solve_seconds = 0.0, function_seconds = 0.0;
  std::vector<std::string> control_names;
  /// The trajectory at t = 0 and every collocation point: t, coordinates, velocities, controls,
  /// multipliers (columns named as `simulate` names them).
  Trajectory trajectory;
  /// N × nu, row-major: the control on each interval (a polynomial control: its mean there).
  std::vector<double> controls;
  /// Per control, whether it is a polynomial on each interval (docs/theory.md §10, "Polynomial
  /// controls").
  std::vector<bool> polynomial;
  /// N × d × nu, row-major: each control at each collocation point (as the trajectory's rows).
  std::vector<double> control_points;
  int intervals = 0, degree = 0;
  /// Ipopt had the exact Hessian of the Lagrangian (a fixed horizon and no option choosing
  /// hessian_approximation), else its limited-memory approximation.
  bool exact_hessian = false;
  /// What looks wrong in the problem but does not stop it, each a located line
  /// ("model.yaml:12:5: warning: control 'G' is used by no equation …").
  std::vector<std::string> warnings;
  /// Why the Hessian is not the exact one when it could have been (empty otherwise).
  std::string hessian_note;
  /// How the exact Hessian's second derivatives ran at the end ("machine code (from the cache)",
  /// "interpreter (…)"); empty without the exact Hessian.
  std::string hessian_evaluation;
  /// How the DAE residual and its first derivatives ran at the end, in the same words.
  std::string residual_evaluation;
  /// The bounds the result lies on (docs/theory.md §10, "Checks"): per bounded quantity and
  /// side, "control 'tau' ≥ -360 at 28 of 40 values", in the order of the variables and rows.
  std::vector<std::string> active_bounds;
  /// H(T) − H(0) against each source's work over [0, T] (docs/theory.md §10, "Checks").
  EnergyBalance energy_balance;
  /// The homotopy's stages before the problem, in order; the fields above are the problem's own
  /// solve (its set-up, solve and function times include the stages').
  std::vector<StageResult> stages;
};

/// Solve `spec` for the model `eq` (compiled as `cm`) with workspace `dyn` (its parameters and
/// Baumgarte rate) from the consistent initial state (q0, v0) (used where `spec` leaves the
/// initial state to the model). std::invalid_argument for a problem the transcription cannot
/// take (saying why); a failure of Ipopt is a result with optimal = false.
OptimizeResult optimize(const Equations& eq, std::shared_ptr<const CompiledModel> cm, Dynamics& dyn,
                        const OptimalControlSpec& spec, const std::vector<double>& q0,
                        const std::vector<double>& v0, const OptimizeOptions& options = {});

/// The result's controls at time t in [0, T] into u (nu values): a piecewise-constant control's
/// value on t's interval, a polynomial control's polynomial there (docs/theory.md §10).
void controls_at(const OptimizeResult& result, double t, double* u);

/// Re-simulate the result's controls (held per interval, or following their polynomials) from its
/// initial state with `options`
/// (the caller's integrator and tolerances): the largest difference of a state component at
/// the final time (`final_gap`) and at the collocation samples (`largest_gap`).
struct VerifyResult {
  double final_gap = 0.0, largest_gap = 0.0;
  std::string message;  ///< empty, or why the simulation failed
};
VerifyResult verify(Dynamics& dyn, const OptimalControlSpec& spec, const OptimizeResult& result,
                    SimulationOptions options);

}  // namespace lagrange
