// Warnings for values a user most likely wrote in the wrong unit (issue 20, item 9): air density
// in g/m³, angles in degrees, gravity in cm/s². The model is read as written; only a line on
// stderr says what looks wrong and what SI value was probably meant.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "compile/ginac_util.hpp"
#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTurn = 2 * kPi;

void print_warning(const SourceLoc& at, const std::string& message) {
  fmt::print(stderr, "{}: warning: {}\n", at.str(), message);
}

/// Where symbols occur, over an expression DAG visited once per distinct node (model expressions
/// of spatial chains share subtrees exponentially often, so a plain recursion would not end):
/// the symbols reached without passing through sin, cos or tan, and those functions' arguments.
class TrigScan {
 public:
  void walk(const GiNaC::ex& e) {
    if (!seen_.emplace(e, true).second) return;
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      outside_.emplace(e, true);
      return;
    }
    if (GiNaC::is_a<GiNaC::function>(e)) {
      const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
      if (name == "sin" || name == "cos" || name == "tan") {
        arguments_.emplace(e.op(0), true);
        return;
      }
    }
    for (size_t i = 0; i < e.nops(); ++i) walk(e.op(i));
  }
  bool outside(const GiNaC::symbol& p) const { return outside_.count(p) > 0; }
  /// An angle: some argument changes with p at a constant rate (sin(p), cos(q + 2 p)), not a
  /// frequency (sin(ω t)). Arguments of more than kSmall distinct nodes are not differentiated.
  bool angle(const GiNaC::symbol& p) const {
    for (const auto& [argument, unused] : arguments_) {
      tape_detail::ExMap<bool> nodes;
      if (!contains(argument, p, nodes) || nodes.size() > kSmall) continue;
      if (GiNaC::is_a<GiNaC::numeric>(argument.diff(p).expand())) return true;
    }
    return false;
  }

 private:
  static constexpr size_t kSmall = 200;
  static bool contains(const GiNaC::ex& e, const GiNaC::symbol& p,
                       tape_detail::ExMap<bool>& nodes) {
    if (nodes.size() > kSmall || !nodes.emplace(e, true).second) return false;
    if (e.is_equal(p)) return true;
    for (size_t i = 0; i < e.nops(); ++i)
      if (contains(e.op(i), p, nodes)) return true;
    return false;
  }
  tape_detail::ExMap<bool> seen_, outside_, arguments_;
};

}  // namespace

void ModelReader::warn_implausible(const GiNaC::ex& e, const YAML::Node& node, Quantity q,
                                   const std::string& what) const {
  const auto implausible = [q](double v) {
    switch (q) {
      case Quantity::AirDensity:
        // 0 switches the aerodynamics off; air is 1.225 kg/m³ at sea level, 0.41 at 10 km.
        return v > 2.0 || (v > 0 && v < 0.01);
      case Quantity::Angle:
        return std::abs(v) > kTurn + 1e-9;
      case Quantity::Gravity:
        return std::abs(v) > 50;
    }
    return false;
  };
  const std::optional<double> v = evaluate_for_test(e, implausible);
  if (!v || !std::isfinite(*v) || !implausible(*v)) return;
  untraceable(e, what + ", which the reader warns about");  // the warning names the value
  const SourceLoc at = src_.at(node);
  switch (q) {
    case Quantity::AirDensity:
      print_warning(
          at, fmt::format("{} is {:g} kg/m³, far outside air's 0.01 … 2 kg/m³ (1.225 "
                          "at sea level): lagrange reads SI units{}",
                          what, *v,
                          *v > 100 ? fmt::format(" ({:g} g/m³ = {:g} kg/m³)", *v, *v / 1000) : ""));
      break;
    case Quantity::Angle:
      print_warning(at, fmt::format("{} is {:g} rad ({:.3g} turns): angles are in radians "
                                    "({:g}° = {:.6g} rad)",
                                    what, *v, *v / kTurn, *v, *v * kPi / 180));
      break;
    case Quantity::Gravity:
      print_warning(
          at, fmt::format("{} is {:g} m/s² ({:.3g} g): lagrange reads SI units "
                          "(9.81 m/s² on Earth){}",
                          what, *v, *v / 9.80665, std::abs(*v) > 500 ? " — cm/s² or ft/s²?" : ""));
      break;
  }
}

void ModelReader::warn_angle_parameters() const {
  const auto beyond_turn = [](double v) { return std::abs(v) > kTurn + 1e-9; };
  // Those beyond a turn, and those a trace follows (another value may be).
  std::vector<const Parameter*> candidates;
  for (const Parameter& p : m_.parameters)
    if (beyond_turn(p.value) || traced(p.sym)) candidates.push_back(&p);
  // Coordinates starting beyond a turn; a joint of links:/urdf: only when a start value set it
  // (the joint's own `initial:` is checked where it is read).
  std::vector<const Coordinate*> coordinates;
  for (const Coordinate& c : m_.coordinates) {
    const int i = static_cast<int>(&c - m_.coordinates.data());
    const bool joint = std::any_of(m_.tree.begin(), m_.tree.end(),
                                   [i](const TreeJoint& j) { return j.coordinate == i; });
    if (beyond_turn(c.initial) && (!joint || start_.count(c.name) != 0)) coordinates.push_back(&c);
  }
  if (candidates.empty() && coordinates.empty()) return;
  TrigScan scan;
  auto visit3 = [&](const Vec3& v) {
    for (const GiNaC::ex& e : v) scan.walk(e);
  };
  scan.walk(m_.kinetic);
  scan.walk(m_.potential);
  for (const GiNaC::ex& e : m_.generalized_forces) scan.walk(e);
  for (const Point& p : m_.points) visit3(p.pos);
  for (const PointForce& f : m_.forces) visit3(f.force);
  for (const Body& b : m_.bodies) {
    visit3(b.position);
    for (const Vec3& row : b.rotation) visit3(row);
  }
  for (const Input& u : m_.inputs) scan.walk(u.expr);
  for (const NamedExpr& c : m_.constraints) scan.walk(c.expr);
  for (const NamedExpr& o : m_.outputs) scan.walk(o.expr);
  if (m_.gravity) visit3(*m_.gravity);
  for (const Parameter* p : candidates) {
    if (scan.outside(p->sym) || !scan.angle(p->sym)) continue;
    if (traced(p->sym)) {
      if (!beyond_turn(evaluate_for_test(p->sym, beyond_turn).value_or(0.0))) continue;
      untraceable(p->sym, "parameter '" + p->name + "', which the reader warns about");
    } else if (!beyond_turn(p->value)) {
      continue;
    }
    print_warning(p->loc,
                  fmt::format("parameter '{}' = {:g} enters only as an angle (inside sin, "
                              "cos or tan) and is {:.3g} turns: angles are in radians "
                              "({:g}° = {:.6g} rad)",
                              p->name, p->value, p->value / kTurn, p->value, p->value * kPi / 180));
  }
  for (const Coordinate* c : coordinates) {
    if (scan.outside(c->q) || !scan.angle(c->q)) continue;
    const auto given = start_.find(c->name);
    const bool by_caller = given != start_.end() && !given->second.in_file;
    const std::string message = fmt::format(
        "initial value of coordinate '{}' is {:g}{} and it enters only as an angle (inside sin, "
        "cos or tan), {:.3g} turns: angles are in radians ({:g}° = {:.6g} rad)",
        c->name, c->initial, by_caller ? ", given to the run," : "", c->initial / kTurn, c->initial,
        c->initial * kPi / 180);
    if (by_caller)
      fmt::print(stderr, "warning: {}\n", message);
    else
      print_warning(given != start_.end() ? src_.at(given->second.key) : c->loc, message);
  }
}

}  // namespace lagrange::model
