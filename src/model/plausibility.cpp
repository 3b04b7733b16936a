// Warnings for values a user most likely wrote in the wrong unit (issue 20, item 9): air density
// in g/m³, angles in degrees, gravity in cm/s². The model is read as written; only a line on
// stderr says what looks wrong and what SI value was probably meant.
#include <fmt/format.h>

#include <cmath>
#include <map>


#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTurn = 2 * kPi;

void print_warning(const SourceLoc& at, const std::string& message) {
  fmt::print(stderr, "{}: warning: {}\n", at.str(), message);
}

/// How each parameter symbol is used: as (part of) a trig function's argument with a numeric
/// coefficient — an angle — and anywhere else.
struct AngleUse {
  bool angle = false, other = false;
};

void scan(const GiNaC::ex& e, const GiNaC::ex& trig_argument,
          std::map<GiNaC::symbol, AngleUse, GiNaC::ex_is_less>& uses) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    const auto& s = GiNaC::ex_to<GiNaC::symbol>(e);
    auto it = uses.find(s);
    if (it == uses.end()) return;
    // An angle when the argument changes with it at a constant rate (sin(p), cos(q + 2 p)), not
    // a frequency (sin(ω t)).
    const bool angle =
        !trig_argument.is_zero() && GiNaC::is_a<GiNaC::numeric>(trig_argument.diff(s).expand());
    (angle ? it->second.angle : it->second.other) = true;
    return;
  }
  GiNaC::ex argument = trig_argument;
  if (GiNaC::is_a<GiNaC::function>(e)) {
    const std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    if (name == "sin" || name == "cos" || name == "tan") argument = e.op(0);
  }
  for (size_t i = 0; i < e.nops(); ++i) scan(e.op(i), argument, uses);
}

}  // namespace

void ModelReader::warn_implausible(const GiNaC::ex& e, const YAML::Node& node, Quantity q,
                                   const std::string& what) const {
  const std::optional<double> v = evaluate(e);
  if (!v || !std::isfinite(*v)) return;
  const SourceLoc at = src_.at(node);
  switch (q) {
    case Quantity::AirDensity:
      // 0 switches the aerodynamics off; air is 1.225 kg/m³ at sea level, 0.41 at 10 km.
      if (*v > 2.0 || (*v > 0 && *v < 0.01))
        print_warning(
            at,
            fmt::format("{} is {:g} kg/m³, far outside air's 0.01 … 2 kg/m³ (1.225 "
                        "at sea level): lagrange reads SI units{}",
                        what, *v,
                        *v > 100 ? fmt::format(" ({:g} g/m³ = {:g} kg/m³)", *v, *v / 1000) : ""));
      break;
    case Quantity::Angle:
      if (std::abs(*v) > kTurn + 1e-9)
        print_warning(at, fmt::format("{} is {:g} rad ({:.3g} turns): angles are in radians "
                                      "({:g}° = {:.6g} rad)",
                                      what, *v, *v / kTurn, *v, *v * kPi / 180));
      break;
    case Quantity::Gravity:
      if (std::abs(*v) > 50)
        print_warning(at, fmt::format("{} is {:g} m/s² ({:.3g} g): lagrange reads SI units "
                                      "(9.81 m/s² on Earth){}",
                                      what, *v, *v / 9.80665,
                                      std::abs(*v) > 500 ? " — cm/s² or ft/s²?" : ""));
      break;
  }
}

void ModelReader::warn_angle_parameters() const {
  std::map<GiNaC::symbol, AngleUse, GiNaC::ex_is_less> uses;
  for (const Parameter& p : m_.parameters)
    if (std::abs(p.value) > kTurn + 1e-9) uses[p.sym];
  if (uses.empty()) return;
  auto visit = [&](const GiNaC::ex& e) { scan(e, 0, uses); };
  auto visit3 = [&](const Vec3& v) {
    for (const GiNaC::ex& e : v) visit(e);
  };
  visit(m_.kinetic);
  visit(m_.potential);
  for (const GiNaC::ex& e : m_.generalized_forces) visit(e);
  for (const Point& p : m_.points) visit3(p.pos);
  for (const PointForce& f : m_.forces) visit3(f.force);
  for (const Body& b : m_.bodies) {
    visit3(b.position);
    for (const Vec3& row : b.rotation) visit3(row);
  }
  for (const Input& u : m_.inputs) visit(u.expr);
  for (const NamedExpr& c : m_.constraints) visit(c.expr);
  for (const NamedExpr& o : m_.outputs) visit(o.expr);
  if (m_.gravity) visit3(*m_.gravity);
  for (const Parameter& p : m_.parameters) {
    auto it = uses.find(p.sym);
    if (it == uses.end() || !it->second.angle || it->second.other) continue;
    print_warning(p.loc, fmt::format("parameter '{}' = {:g} enters only as an angle (inside sin, "
                                     "cos or tan) and is {:.3g} turns: angles are in radians "
                                     "({:g}° = {:.6g} rad)",
                                     p.name, p.value, p.value / kTurn, p.value,
                                     p.value * kPi / 180));
  }
}

}  // namespace lagrange::model
