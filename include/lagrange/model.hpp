#pragma once
// The symbolic model: what a user wrote, as GiNaC expressions, before any derivation.

#include <ginac/ginac.h>

#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "lagrange/error.hpp"
#include "lagrange/optimal_control.hpp"

namespace lagrange {

/// A 3-vector of symbolic expressions (world frame).
using Vec3 = std::array<GiNaC::ex, 3>;

/// A 3×3 matrix of symbolic expressions, row-major (rows are Vec3).
using Mat3 = std::array<Vec3, 3>;

/// A named symbolic constant whose value can change without a new derivation.
struct Parameter {
  std::string name;
  GiNaC::symbol sym;
  double value = 0.0;
  SourceLoc loc;
};

/// A generalised coordinate q with its velocity v = q̇ and acceleration a = q̈ symbols.
struct Coordinate {
  std::string name;
  GiNaC::symbol q, v, a;
  double initial = 0.0;
  double rate = 0.0;
  bool fixed = false;  ///< kept unchanged when an inconsistent initial state is projected
  SourceLoc loc;
};

/// A prescribed signal u(t) with symbols for u, u̇ and ü; `expr` is a function of t and parameters.
struct Input {
  std::string name;
  GiNaC::symbol u, ud, udd;
  GiNaC::ex expr;  ///< u(t); for an external input, its value when no caller sets it
  SourceLoc loc;
  bool external = false;  ///< set by a caller between steps (include/lagrange/stepper.hpp)
};

/// A named point (position vector in the world frame as a function of q, t, u, p).
struct Point {
  std::string name;
  Vec3 pos;
  SourceLoc loc;
};

/// A point mass m at a named point: adds ½ m |vel|² (and m g·x when gravity is set).
/// `gravity = false` makes it a pure inertia term (e.g. a rod's rotary inertia, docs/theory.md
/// §4.5).
struct Particle {
  std::string point;
  GiNaC::ex mass;
  SourceLoc loc;
  bool gravity = true;
};

/// A world-frame force applied at a point; turned into Q by virtual work (docs/theory.md §4.2).
struct PointForce {
  std::string point;
  Vec3 force;
  SourceLoc loc;
};

/// A linear spring between two points: U = ½ k (|b − a| − l0)².
struct Spring {
  std::string a, b;
  GiNaC::ex k, l0;
  SourceLoc loc;
};

/// A linear damper between two points: Rayleigh D = ½ c ḋ², Q = −∂D/∂q̇, d = |b − a|.
struct Damper {
  std::string a, b;
  GiNaC::ex c;
  SourceLoc loc;
};

/// A rigid body (docs/theory.md §4.4). Free bodies own their coordinates: q ⊃ r (3) and the nine
/// entries of R (row-major), v ⊃ ṙ (3) and the body-frame ω (3). Posed bodies follow
/// `position` and `rotation`, expressions of the model's coordinates and t.
struct Body {
  std::string name;
  GiNaC::ex mass;
  Mat3 inertia;       ///< inertia tensor about the centre of mass, body axes
  Vec3 com{0, 0, 0};  ///< centre of mass in body axes, from the body origin
  bool free = false;
  std::array<GiNaC::symbol, 3> r, rd, rdd;  ///< free: origin, its velocity and acceleration
  std::array<GiNaC::symbol, 9> R;           ///< free: rotation body → world, row-major
  std::array<GiNaC::symbol, 3> w, wd;       ///< free: body-frame ω and ω̇
  std::array<double, 3> r0{}, v0{}, w0{};   ///< free: initial r, ṙ, ω (body frame)
  std::array<double, 9> R0{1, 0, 0, 0, 1, 0, 0, 0, 1};  ///< free: initial R
  Vec3 position{0, 0, 0};  ///< posed: world position of the body origin
  Mat3 rotation{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};  ///< posed: rotation body → world
  /// Posed: the body-frame angular velocity U(RᵀṘ) when an element composes it along a chain
  /// (ω_child = R_relᵀ ω_parent + k q̇, docs/theory.md §4.8); unset, it is derived from R (§4.4).
  std::optional<Vec3> angular_velocity;
  /// The `shape:` declared for a `bodies:` entry (box, cylinder or sphere), or "" (an inertia).
  std::string shape;
  SourceLoc loc;

  /// Make this a free body with fresh symbols named `<name>.x`, `<name>.R11`, `<name>.wx`, ….
  void make_free();
  /// World position of the body origin (symbols for a free body).
  Vec3 origin() const;
  /// Rotation body → world (symbols for a free body).
  Mat3 rot() const;
  /// World position of the body-fixed point p_b: r + R p_b.
  Vec3 world_point(const Vec3& p_body) const;
};

/// A joint of a kinematic tree (docs/theory.md §4.9): it places a link frame in its parent's
/// frame and moves it about (revolute) or along (prismatic) a unit axis. Elements that build
/// joint chains describe them so; the recursive formulation needs nothing else.
struct TreeJoint {
  enum class Kind { Revolute, Prismatic, Fixed } kind = Kind::Fixed;
  int parent = -1;       ///< index in Model::tree of the parent link's joint, −1 for the world
  int coordinate = -1;   ///< index in Model::coordinates of the joint's q, −1 when fixed
  int body = -1;         ///< index in Model::bodies of the link's body, −1 for a massless link
  Vec3 axis{0, 0, 1};    ///< unit joint axis in the link frame (motion subspace)
  Vec3 origin{0, 0, 0};  ///< link frame origin in the parent frame (q in it when prismatic)
  Mat3 rotation{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};  ///< link axes in the parent
                                                               ///< frame (q in it when revolute)
};

/// A torque on a body, in the world frame or the body frame; enters by virtual power
/// τ·ω (docs/theory.md §4.2, §4.4: F_rot = 2P(F_R)).
struct BodyTorque {
  std::string body;
  Vec3 torque;
  bool body_frame = false;
  SourceLoc loc;
};

/// A named scalar expression (constraint C = 0, or an output to record).
struct NamedExpr {
  std::string name;
  GiNaC::ex expr;
  SourceLoc loc;
};

/// An output column λ_c · scale(q, t): the physical size of a constraint force (a tether
/// segment's tension λ ℓ_s for C = ½(|d|² − ℓ_s²)), recorded after the multipliers.
struct Reaction {
  std::string name;
  size_t constraint = 0;  ///< index into Model::constraints
  GiNaC::ex scale;
  SourceLoc loc;
};

/// One signed force component of a Load: `expr` (in t, q, v, u, p and, linearly, the
/// coordinates' acceleration symbols `a`) plus Σ λ_c · coefficient over `multipliers`
/// (constraint index, coefficient in t, q, v, u, p).
struct LoadPart {
  GiNaC::ex expr;
  std::vector<std::pair<size_t, GiNaC::ex>> multipliers;
};

/// An output column that a load cell would read (docs/theory.md §4.11): one part is a signed
/// force, three parts are a force vector whose length is recorded. Needs the solved a and λ.
struct Load {
  std::string name;
  std::vector<LoadPart> parts;
  SourceLoc loc;
};

/// What an element lowered into the model, for `derive` to show in readable form: a title, a
/// few representative equations (one segment's, not N copies) and plain-text notes.
struct ElementSummary {
  std::string title;
  std::vector<std::pair<std::string, GiNaC::ex>> equations;
  std::vector<std::string> notes;
};

/// A `stop_when:` condition as written, `lhs < rhs` or `lhs > rhs` over trajectory columns;
/// compiled once the columns are known (lagrange/stop_conditions.hpp).
struct StopSpec {
  std::string name, text;
  SourceLoc loc;  ///< of the condition's text
};

/// A `metrics:` entry as written, `AGG(EXPR[, WINDOW])` over trajectory columns and parameters;
/// aggregated per case by `lagrange sweep` (lagrange/sweep.hpp) and printed by `simulate`.
struct MetricSpec {
  std::string name, text;
  SourceLoc loc;  ///< of the metric's text
};

/// Constraint stabilisation settings (docs/theory.md §4.3).
struct Stabilization {
  /// Baumgarte: both eigenvalues of the constraint error at −α; unset, baumgarte_rate() chooses.
  std::optional<double> alpha;
  bool project = true;  ///< project onto C = 0, Ċ = 0 after steps and at output samples
  double gamma = 1.0;   ///< SO(3) orthonormality drift correction rate (docs/theory.md §4.4)
  SourceLoc loc;
};

/// Integration settings from the `simulate:` key (CLI flags override them).
struct SimulateOptions {
  double t_end = 10.0;
  double output_step = 0.01;
  std::string integrator = "dop853";  ///< one of integrator_methods()
  double rtol = 1e-8;
  double atol = 1e-10;
  double step = 0.0;  ///< fixed step for rk4; 0 means output_step / 10
  int max_order = 5;  ///< the highest order of the BDF methods (cvode*, ida*), 1 to 5
  SourceLoc loc;
};

/// The `visual:` section (docs/model-language.md, "How a model looks") as the reader checked it:
/// how the report draws points, bodies and elements (a name up to '.': `cable` for `cable.n3`).
struct Visual {
  std::map<std::string, std::string> color;  ///< name → CSS colour as written
  std::map<std::string, double> size;        ///< name → radius (points) or scale (bodies), > 0
  std::vector<std::string> trail, hide;      ///< names whose paths are drawn; names not drawn
  bool trail_given = false;                  ///< `trail:` was written (even empty)
};

/// Everything a user described; immutable once read. Symbols are owned here.
struct Model {
  std::string name;
  std::string file;
  GiNaC::symbol t{"t"};
  std::vector<Parameter> parameters;
  std::vector<Coordinate> coordinates;
  std::vector<Input> inputs;
  std::vector<Point> points;
  GiNaC::ex kinetic = 0;    ///< user-written kinetic energy (added to the particles')
  GiNaC::ex potential = 0;  ///< user-written potential energy (added to gravity's and springs')
  std::vector<GiNaC::ex> generalized_forces;  ///< one per coordinate (0 when absent)
  std::vector<Particle> particles;
  std::optional<Vec3> gravity;
  std::vector<PointForce> forces;
  std::vector<Spring> springs;
  std::vector<Damper> dampers;
  std::vector<Body> bodies;
  std::vector<BodyTorque> torques;
  /// Joints of kinematic trees whose links are bodies above (parents before children); the
  /// bodies keep their own poses, this is the same motion told joint by joint.
  std::vector<TreeJoint> tree;
  std::vector<NamedExpr> constraints;
  std::vector<NamedExpr> outputs;
  std::vector<Reaction> reactions;
  std::vector<Load> loads;  ///< load-cell columns (winch drums, tether anchors)
  std::vector<ElementSummary> element_summaries;
  Stabilization stabilization;
  SimulateOptions simulate;
  std::vector<StopSpec> stop_when;  ///< `stop_when:` conditions, in file order
  std::vector<MetricSpec> metrics;  ///< `metrics:`, in file order
  Visual visual;                    ///< `visual:`, empty when not written
  /// `optimal_control:`, what `lagrange optimize` solves; unset when not written.
  std::optional<OptimalControlSpec> optimal_control;
  /// Conditions that leave an element's physical domain (a winch's reeled-out length below 0),
  /// added by the elements: a run fails, located in time, where one becomes true. The name says
  /// what went wrong; loc is the element's.
  std::vector<StopSpec> fail_when;
  /// Conditions under which an element's model stops being physical without failing the run (a
  /// kite below the ground of its wind profile): the first sample where one holds adds a warning.
  std::vector<StopSpec> warn_when;

  /// Index of a named entity, or -1.
  int coordinate_index(const std::string& name) const;
  int parameter_index(const std::string& name) const;
  int input_index(const std::string& name) const;
  const Point* find_point(const std::string& name) const;
  const Body* find_body(const std::string& name) const;

  /// Total time derivative d/dt of an expression in (t, q, v, u, u̇, p):
  /// Σ ∂e/∂q v + ∂e/∂v a + ∂e/∂u u̇ + ∂e/∂u̇ ü + ∂e/∂t, with ṙ, ω̇ and Ṙ = RΩ for free bodies
  /// (docs/theory.md §4.4). Fails (std::logic_error) on q̈, ü and body accelerations.
  GiNaC::ex time_derivative(const GiNaC::ex& e) const;
};

}  // namespace lagrange
