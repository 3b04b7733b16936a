#pragma once
// The `optimal_control:` section of a model file as the reader checked it (docs/model-language.md,
// "Optimal control"): what `lagrange optimize` solves (lagrange/optimize.hpp).

#include <ginac/ginac.h>

#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "lagrange/error.hpp"

namespace lagrange {

/// Lower and upper bounds, infinite when not written.
struct Bounds {
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

/// A model input the optimiser chooses, constant on each collocation interval, a polynomial on
/// each (`polynomial`), or constant over the whole horizon (`constant`: a design value such as a
/// gain, a stiffness or a drum radius).
struct ControlSpec {
  size_t input = 0;  ///< index into Model::inputs
  Bounds bounds;
  std::optional<double> guess;  ///< initial guess (else 0 clipped to the bounds)
  bool constant = false;        ///< one value for the whole horizon
  SourceLoc loc;
  /// A value at each collocation point, the degree d − 1 polynomial through them on each interval
  /// (docs/theory.md §10, "Polynomial controls").
  bool polynomial = false;
};

/// A coordinate (`velocity` false) or its rate NAME_dot, by index into Model::coordinates; or a
/// free body's component by its state name (`body_state`: `<body>.x` … `<body>.R33`, `<body>.vx` …
/// `<body>.wz`), `coordinate` then unused.
struct StateRef {
  size_t coordinate = 0;
  bool velocity = false;
  std::string body_state;
  SourceLoc loc;
};

/// A bound on a coordinate or a rate, held at every collocation point.
struct StateBound {
  StateRef state;
  Bounds bounds;
};

/// A boundary condition on a state component at the start or the end: fixed (lower = upper)
/// or bounded.
struct BoundaryValue {
  StateRef state;
  Bounds bounds;
  bool fixed() const { return bounds.lower == bounds.upper; }
};

/// lower ≤ expr(t, q, v, u, λ, p) ≤ upper at every collocation point.
struct PathConstraintSpec {
  std::string name;
  GiNaC::ex expr;
  Bounds bounds;
  SourceLoc loc;
};

/// One step of a homotopy (docs/theory.md §10, "Homotopy"), solved before the problem itself and
/// warm-starting the next: the problem with its objective replaced (`replaces_objective`), some
/// controls' bounds replaced (a fictitious force let free, then fixed at 0), a weight `track` on
/// the states' distance from the stage's starting point, and Ipopt options of its own.
struct StageSpec {
  std::string name;
  bool replaces_objective = false;
  bool maximize = false;
  GiNaC::ex integrand = 0, terminal = 0, mean_integrand = 0;  ///< as OptimalControlSpec's
  std::string objective_text;
  std::vector<std::pair<size_t, Bounds>> control_bounds;  ///< (index into controls, bounds)
  double track = 0.0;
  std::vector<std::pair<std::string, std::string>> ipopt;  ///< after the command line's
  /// A free horizon's bounds in this stage (lower = upper: T held there); unset: the problem's.
  std::optional<Bounds> horizon;
  SourceLoc loc;
};

/// The problem: J = ∫₀ᵀ L dt + (1/T)∫₀ᵀ M dt + Φ(T, q(T), v(T), u(T)), minimised (or maximised)
/// subject to the dynamics, bounds, path constraints and boundary values (docs/theory.md §10).
struct OptimalControlSpec {
  std::vector<ControlSpec> controls;
  /// λ_c of each model constraint, as the objective and path expressions use them (a constraint's
  /// name, or a reaction λ_c·scale such as a tether's tension).
  std::vector<GiNaC::symbol> multipliers;
  double horizon = 1.0;                ///< T when fixed; the initial guess when free
  std::optional<Bounds> free_horizon;  ///< set: T is chosen within these bounds
  bool maximize = false;
  GiNaC::ex integrand = 0;  ///< L, the sum of the objective's integral terms with their factors
  GiNaC::ex terminal = 0;   ///< Φ, the rest of the objective (t is the final time there)
  /// M, the sum of the objective's mean(…) terms with their factors: (1/T)∫₀ᵀ M dt, T free or not
  GiNaC::ex mean_integrand = 0;
  std::string objective_text;
  std::vector<StateBound> bounds;
  std::vector<PathConstraintSpec> path;
  /// Unset: the model's initial state, all fixed; set: only the listed components are fixed or
  /// bounded.
  std::optional<std::vector<BoundaryValue>> initial;
  std::vector<BoundaryValue> final;
  /// x(T) = x(0) for these components (`periodic: true`: every coordinate and rate); with
  /// constraints only those the invariants leave independent are imposed (docs/theory.md §10,
  /// "Periodic problems").
  std::vector<StateRef> periodic;
  /// The starting point: "linear" interpolation between the boundary states, a "simulation" of
  /// the model (controls with a guess held at it, the others on their declared expressions), or
  /// "" (simulation for constrained models,
  /// whose states a straight line would take off the constraints; linear otherwise).
  std::string guess;
  /// `guess: {COORDINATE: expr(t), …}`: those coordinates start on the written paths, their rates
  /// on the paths' time derivatives; the others interpolate linearly (docs/theory.md §10).
  std::vector<std::pair<StateRef, GiNaC::ex>> guess_paths;
  /// `guess: FILE.csv`: a trajectory CSV (an earlier solution, a simulation) whose coordinate,
  /// rate and control columns start the solve, stretched over the horizon; the path resolved
  /// against the model file's folder.
  std::string guess_file;
  /// Homotopy stages solved in order before the problem, each from the last one's result.
  std::vector<StageSpec> stages;
  int intervals = 50;  ///< collocation intervals N
  int degree = 3;      ///< Radau IIA collocation points per interval
  SourceLoc loc;
};

}  // namespace lagrange
