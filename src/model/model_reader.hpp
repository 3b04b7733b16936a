#pragma once
// The YAML → Model reader's internals, split over read_*.cpp by section (docs/model-language.md).

#include <yaml-cpp/yaml.h>

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lagrange/model.hpp"
#include "lagrange/reader.hpp"
#include "lagrange/rigid_body.hpp"
#include "model/expression_parser.hpp"
#include "model/source_text.hpp"

namespace lagrange::model {

/// A section's node, or nothing when the key is absent or has no value.
inline std::optional<YAML::Node> section(const YAML::Node& root, const char* key) {
  YAML::Node n = root[key];
  if (!n || n.IsNull()) return std::nullopt;
  return n;
}

/// What a user-chosen name denotes. Derived: NAME_dot / NAME_ddot of a coordinate or input;
/// BodyPoint: `body.point`, a point declared in a body's `points`.
enum class NameKind {
  Parameter,
  Coordinate,
  Input,
  Point,
  Constraint,
  Output,
  Derived,
  Body,
  BodyPoint,
  Element
};

/// A declared name: its kind, index in the Model's list of that kind, and where it was written.
struct NameEntry {
  NameKind kind;
  size_t index;
  SourceLoc loc;
  std::string owner;  ///< for Derived: the coordinate or input it belongs to
};

/// Which names an expression may use (bit set); pi and numbers are always allowed.
enum Allowed : unsigned {
  kNumbers = 0,
  kParams = 1,
  kTime = 2,
  kCoords = 4,
  kInputs = 8,
  kPoints = 16,
  kAll = 31,
  /// The trajectory's columns beyond the state: outputs, constraint multipliers (by the
  /// constraint's name) and reactions such as tether tensions (optimal control only).
  kColumns = 32
};

/// Reads one YAML document into a Model. Sections are read in dependency order:
/// parameters, coordinates, inputs, points, then everything that may use them.
class ModelReader {
 public:
  /// `trace`, when given, records how the model depends on the watched parameters' values.
  ModelReader(const SourceText& src, const ParameterOverrides& overrides,
              ReadTrace* trace = nullptr, const StartValues& start = {});
  Model read(const YAML::Node& root);

  // The methods below are also the interface of the element readers (src/elements/), which
  // read their own sections and lower into the model through them.

  // yaml_nodes.cpp — node shape checks, all failing with the node's location.
  [[noreturn]] void fail(const YAML::Node& node, const std::string& message) const;
  std::string describe(const YAML::Node& node) const;
  void expect_map(const YAML::Node& node, const std::string& what) const;
  void expect_seq(const YAML::Node& node, const std::string& what) const;
  std::string scalar(const YAML::Node& node, const std::string& what) const;
  bool boolean(const YAML::Node& node, const std::string& what) const;
  /// Checks that `map` is a map whose keys are distinct scalars from `valid` (empty: any).
  void check_keys(const YAML::Node& map, const std::vector<std::string>& valid,
                  const std::string& where) const;

  // reader_names.cpp — one namespace for parameters, coordinates, inputs, points, constraints,
  // outputs.
  void declare(const std::string& name, NameKind kind, size_t index, const YAML::Node& key,
               const std::string& owner = "");
  /// The same, for a name written at `loc` (a generated name, or one from another file).
  void declare_at(const std::string& name, NameKind kind, size_t index, const SourceLoc& loc,
                  const std::string& owner = "");
  void declare_all(const YAML::Node& root);
  std::optional<Value> lookup(const std::string& name, size_t offset, unsigned allowed) const;
  /// `body.r`, `body.R` for a dotted name whose first part is a body; nullopt otherwise.
  std::optional<Value> body_member(const std::string& name, size_t offset, unsigned allowed) const;
  /// An output, a constraint's multiplier λ_c or a reaction λ_c·scale named as its column.
  std::optional<Value> column_value(const std::string& name, size_t offset) const;
  /// Declares `body.point` (the point's own name checked like any other name).
  void declare_body_point(const std::string& body, const YAML::Node& key, size_t index);
  std::string names_of(NameKind kind) const;

  // reader_expressions.cpp — expressions inside YAML scalars.
  /// Names an element defines for its own expressions (a kite's `alpha`), found before the
  /// model's names.
  using LocalNames = std::map<std::string, GiNaC::ex>;
  Value parse(const YAML::Node& node, unsigned allowed, const std::string& what,
              const LocalNames* locals = nullptr) const;
  /// parse() of `text` in place of the node's own scalar, errors located in the node: `text` has
  /// the scalar's length with parts blanked or renamed (offsets unchanged).
  Value parse_text(const YAML::Node& node, const std::string& text, unsigned allowed,
                   const std::string& what, const LocalNames* locals = nullptr) const;
  GiNaC::ex scalar_expr(const YAML::Node& node, unsigned allowed, const std::string& what,
                        const LocalNames* locals = nullptr) const;
  Vec3 vector_expr(const YAML::Node& node, unsigned allowed, const std::string& what) const;
  /// A 3×3 matrix: a YAML list of three rows [x, y, z], or one matrix expression.
  Mat3 matrix_expr(const YAML::Node& node, unsigned allowed, const std::string& what) const;
  double number(const YAML::Node& node, unsigned allowed, const std::string& what) const;
  /// The value of `e` at the file's parameter values, if it is a real number.
  std::optional<double> evaluate(const GiNaC::ex& e) const;

  // read_trace.cpp — how the model depends on the values of a trace's watched parameters
  // (docs/theory.md §9.4). Untraced reads skip all of it.
  /// `e` depends on a watched value: a watched parameter, a coordinate whose initial value or
  /// rate is an expression of one, an input whose expression uses one.
  bool traced(const GiNaC::ex& e) const;
  /// Records in the trace that `e`'s value went where it cannot be recomputed (`what`), when it
  /// depends on a watched value.
  void untraceable(const GiNaC::ex& e, const std::string& what) const;
  /// evaluate(e) for a test whose answer is all the reader uses of the value (`test(value)`
  /// true: the reader fails or warns): a traced read keeps the test to repeat it.
  std::optional<double> evaluate_for_test(const GiNaC::ex& e,
                                          const std::function<bool(double)>& test) const;
  /// A coordinate's initial value (`rate` false) or rate written at `node`, as number() reads
  /// it; a traced read keeps its expression when it depends on a watched parameter.
  /// `c` is the coordinate being read (the next of the model's).
  double coordinate_number(const YAML::Node& node, const std::string& what, const Coordinate& c,
                           bool rate);
  /// Starts following the trace's watched parameters (once the parameters are read).
  void watch_parameters();
  /// check_body_inertia (lagrange/rigid_body.hpp) on `body`, whose mass and inertia a trace
  /// cannot follow.
  void check_inertia(const Body& body, std::optional<size_t> spin_axis) const;
  /// Fails at `node` if `e` evaluates to a number that is negative (or zero when `strict`).
  void check_sign(const GiNaC::ex& e, const YAML::Node& node, bool strict,
                  const std::string& what) const;
  std::string point_name(const YAML::Node& node, const std::string& what) const;

  // plausibility.cpp — warnings (not errors) for values far outside physical ranges, printed as
  // "file:line:column: warning: …" on stderr; the model is read as written.
  enum class Quantity { AirDensity, Angle, Gravity };
  /// Warns at `node` when `e` evaluates to a value implausible for `q` (kg/m³, rad, m/s²).
  void warn_implausible(const GiNaC::ex& e, const YAML::Node& node, Quantity q,
                        const std::string& what) const;
  /// Warns for each parameter, and each coordinate's start value, above one turn that enters only
  /// as an angle (sin(p), cos(q + p), …).
  void warn_angle_parameters() const;

  // read_start.cpp — start values: the file's `initial:` section and the caller's (which win).
  /// Evaluates both at the parameters' values (a located error, or ValueTextError for the
  /// caller's); `section` is the file's `initial:` map, if written.
  void read_start_values(const std::optional<YAML::Node>& section);
  /// The start value given for a coordinate or rate `name`, or `otherwise`.
  double start_value(const std::string& name, double otherwise);
  /// A located error at the first name of the file's `initial:` that named no coordinate or rate.
  void check_start_values_used() const;

  // read_declarations.cpp
  void read_parameters(const YAML::Node& node);
  /// Every override names a parameter (ParameterOverrideError otherwise).
  void check_overrides() const;
  void read_coordinates(const YAML::Node& node);
  void read_inputs(const YAML::Node& node);
  // read_points.cpp
  void read_points(const YAML::Node& node);
  // read_equations.cpp
  void read_energies(const YAML::Node& root);
  void read_generalized_forces(const YAML::Node& node);
  std::vector<NamedExpr> read_named(const YAML::Node& node, const std::string& section);
  // read_elements.cpp
  void read_particles(const YAML::Node& node);
  void read_forces(const YAML::Node& node);
  void read_springs(const YAML::Node& node);
  void read_dampers(const YAML::Node& node);
  std::pair<std::string, std::string> read_between(const YAML::Node& item, const std::string& what);
  // read_bodies.cpp — rigid bodies and torques (docs/theory.md §4.4).
  void read_bodies(const YAML::Node& node);
  Body read_body(const std::string& name, const YAML::Node& key, const YAML::Node& spec);
  Mat3 read_inertia(const Body& body, const YAML::Node& spec);
  Mat3 read_shape(const Body& body, const YAML::Node& shape);
  void read_body_points(Body& body, const YAML::Node& node);
  // posed_rotation.cpp — a posed body's rotation judged numerically at a few states.
  /// Values of every symbol at one state, and the coordinates' and t's values by name.
  struct SampledState {
    GiNaC::exmap values;
    std::map<std::string, double> shown;
    bool initial = false;
  };
  /// The initial state and a few drawn around it (fixed seed).
  std::vector<SampledState> sample_states() const;
  /// RᵀR = 1 and det R = +1 at the sampled states, or a located error saying what was found.
  void check_posed_rotation(const Body& body, const YAML::Node& node) const;
  /// Records in a trace that `body`'s rotation, when it depends on a watched value, is judged at
  /// sampled states (which a trace cannot follow).
  void untraced_rotation(const Body& body) const;
  /// The body axis the angular velocity always lies along (z for rot_z(q)), if any.
  std::optional<size_t> single_spin_axis(const Body& body) const;
  void read_torques(const YAML::Node& node);
  // read_body_initial.cpp — the initial state of a free body.
  void read_free_initial(Body& body, const YAML::Node& node);
  Rotation read_orientation(const Body& body, const YAML::Node& node);
  std::array<double, 3> numeric_vector(const YAML::Node& node, const std::string& what) const;
  // read_settings.cpp
  void read_stabilization(const YAML::Node& node);
  void read_simulate(const YAML::Node& node);
  /// `stop_when: {name: "lhs < rhs"}`: the texts, checked for one comparison; their names are
  /// checked against the trajectory columns once the model is compiled.
  void read_stop_when(const YAML::Node& node);
  /// `metrics: {name: AGG(EXPR[, WINDOW])}`, kept as text: their names are the trajectory's
  /// columns, known once the model is compiled (src/sweep/metrics.cpp checks them).
  void read_metrics(const YAML::Node& node);
  // read_visual.cpp
  /// `visual: {color, size, trail, hide}`: names of points, bodies or elements, CSS colours,
  /// positive sizes; read by the report, checked here so that `check` finds its mistakes.
  void read_visual(const YAML::Node& node);
  // read_optimal_control.cpp — the problem `lagrange optimize` solves (docs/model-language.md).
  void read_optimal_control(const YAML::Node& node);
  /// A coordinate NAME or its rate NAME_dot named by the scalar `node`, or a located error.
  StateRef state_ref(const YAML::Node& node, const std::string& what) const;
  /// `{lower: …, upper: …}` (each optional, numbers of parameters), lower ≤ upper.
  Bounds read_bounds(const YAML::Node& node, const std::string& what,
                     const std::vector<std::string>& extra_keys = {}) const;
  /// The objective `text` at `node`: integral(…) terms with constant factors, plus terminal terms.
  void read_objective(const YAML::Node& node, OptimalControlSpec& spec) const;
  // read_stages.cpp
  /// `stages:`, the homotopy's list of `{name, minimize or maximize, controls, track, ipopt}`
  /// (docs/model-language.md, "Homotopy stages"), into spec.stages.
  void read_stages(const YAML::Node& node, OptimalControlSpec& spec) const;

  // read_generated.cpp — names and state that elements generate (docs/model-language.md).
  Model& model() { return m_; }
  const SourceText& source() const { return src_; }
  /// Declares an element's own name (`tethers: {main: …}` declares `main`).
  void declare_element(const YAML::Node& key);
  /// A generated point `<owner>.<member>` (dotted, so it cannot clash with user names).
  void add_point(const std::string& name, const Vec3& pos, const YAML::Node& at);
  void add_point(const std::string& name, const Vec3& pos, const SourceLoc& loc);
  /// A generated coordinate named `name` (dotted) with its initial value and rate; returns it.
  const Coordinate& add_coordinate(const std::string& name, double initial, double rate,
                                   const YAML::Node& at);
  const Coordinate& add_coordinate(const std::string& name, double initial, double rate,
                                   const SourceLoc& loc);
  /// A coordinate under a name of the user's (a joint's), declared and checked like one written
  /// in `coordinates:` (with its `_dot` and `_ddot`).
  const Coordinate& add_named_coordinate(const std::string& name, double initial, double rate,
                                         const SourceLoc& loc);
  /// A generated posed body under a checked name: `body.r`, `body.R` work in expressions.
  void add_body(const Body& body);
  /// The value of `e` at t = 0 and the initial state (coordinates, free bodies, inputs), with
  /// the file's parameter values; nullopt when it is not a finite real number.
  std::optional<double> initial_value(const GiNaC::ex& e) const;
  /// Kind of a declared name, if any.
  std::optional<NameKind> kind_of(const std::string& name) const;

 private:
  const SourceText& src_;
  const ParameterOverrides& overrides_;
  ReadTrace* trace_ = nullptr;
  const StartValues& given_start_;
  /// A start value by name; `key` is its name in the file's `initial:` when `in_file`.
  struct Start {
    double value = 0.0;
    YAML::Node key;
    bool in_file = false;
    bool used = false;
  };
  std::map<std::string, Start> start_;
  /// The symbols whose values a trace follows (watched parameters, then coordinates' q or v).
  std::vector<GiNaC::symbol> traced_symbols_;
  /// evaluate(e) without recording anything in a trace.
  std::optional<double> evaluate_unrecorded(const GiNaC::ex& e) const;
  /// A real, finite value of `e` at the parameters' values as evaluate() gives it and a tape
  /// over the parameters recomputes it, or nothing.
  std::optional<double> replayable_value(const GiNaC::ex& e) const;
  /// The number of `e`, written at `node`, or a located error (not real, not finite).
  double checked_number(const std::optional<double>& v, const YAML::Node& node,
                        const std::string& what) const;
  Model m_;
  std::map<std::string, NameEntry> names_;
  std::vector<bool> point_ready_;
  /// λ_c of each constraint while optimal_control is read (kColumns).
  std::vector<GiNaC::symbol> multipliers_;
  std::vector<Point> body_points_;  ///< `body.point` in the world frame, appended to the points
  std::vector<bool> body_ready_;
};

}  // namespace lagrange::model
