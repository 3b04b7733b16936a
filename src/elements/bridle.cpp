// `bridles:` (docs/model-language.md, "Bridles"; docs/theory.md §4.7): lines of fixed length
// from points of a kite to a knot, a point with coordinates of its own where the main tether
// starts or ends. Each line is the distance constraint ½(|r_k − p_i|² − ℓ_i²); the lines carry
// no mass (a knot `mass:` may stand for theirs).

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "elements/tether.hpp"
#include "model/model_reader.hpp"

namespace lagrange::elements {

using model::ModelReader;

namespace {

using Num3 = std::array<double, 3>;

const std::vector<std::string>& bridle_keys() {
  static const std::vector<std::string> keys{"lines", "length", "at", "mass"};
  return keys;
}

/// The line lengths: one expression for every line, or a list with one per line.
std::vector<GiNaC::ex> line_lengths(ModelReader& r, const ElementEntry& e, size_t lines) {
  const YAML::Node& node = e.spec["length"];
  if (!node) r.fail(e.key, fmt::format("expected 'length' (of the lines) in {}, got none", e.what));
  std::vector<GiNaC::ex> lengths;
  const std::string what = "line length of " + e.what;
  if (!node.IsSequence()) {
    const GiNaC::ex l = r.scalar_expr(node, model::kParams, what);
    r.check_sign(l, node, true, what);
    return std::vector<GiNaC::ex>(lines, l);
  }
  if (node.size() != lines)
    r.fail(node, fmt::format("expected {} line lengths (one per line) in {}, got {}", lines, e.what,
                             node.size()));
  for (const auto& item : node) {
    lengths.push_back(r.scalar_expr(item, model::kParams, what));
    r.check_sign(lengths.back(), item, true, what);
  }
  return lengths;
}

std::vector<std::string> line_points(ModelReader& r, const ElementEntry& e) {
  const YAML::Node& node = e.spec["lines"];
  if (!node) r.fail(e.key, fmt::format("expected 'lines' (the points they run to) in {}", e.what));
  r.expect_seq(node, "lines of " + e.what + " (a list of one to three points)");
  if (node.size() < 1 || node.size() > 3)
    r.fail(node, fmt::format("expected one to three lines in {} (more would over-determine the "
                             "knot), got {}",
                             e.what, node.size()));
  std::vector<std::string> points;
  for (const auto& item : node) points.push_back(r.point_name(item, "a line of " + e.what));
  return points;
}

Num3 initial_of(ModelReader& r, const Vec3& pos, const YAML::Node& node, const std::string& what) {
  Num3 x{};
  for (size_t k = 0; k < 3; ++k) {
    const auto v = r.initial_value(pos[k]);
    if (!v) r.fail(node, fmt::format("expected {} to have a finite value at t = 0", what));
    x[k] = *v;
  }
  return x;
}

double det3(const std::vector<Num3>& d) {
  return d[0][0] * (d[1][1] * d[2][2] - d[1][2] * d[2][1]) -
         d[0][1] * (d[1][0] * d[2][2] - d[1][2] * d[2][0]) +
         d[0][2] * (d[1][0] * d[2][1] - d[1][1] * d[2][0]);
}

double norm(const Num3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// The lines must hold the knot independently at t = 0: their directions from the knot are
// linearly independent (else the constraints' Jacobian loses rank).
void check_independent(ModelReader& r, const ElementEntry& e, const std::vector<Num3>& d) {
  double measure = 1;  // |det| of the unit directions (three), |sin| of their angle (two)
  std::vector<Num3> unit;
  for (const Num3& v : d) unit.push_back({v[0] / norm(v), v[1] / norm(v), v[2] / norm(v)});
  if (unit.size() == 3) measure = std::abs(det3(unit));
  if (unit.size() == 2)
    measure = norm({unit[0][1] * unit[1][2] - unit[0][2] * unit[1][1],
                    unit[0][2] * unit[1][0] - unit[0][0] * unit[1][2],
                    unit[0][0] * unit[1][1] - unit[0][1] * unit[1][0]});
  if (measure < 1e-6)
    r.fail(e.spec["lines"],
           fmt::format("expected lines of {} in independent directions from the "
                       "knot at t = 0 (two not parallel, three not in one "
                       "plane), got {}",
                       e.what, unit.size() == 3 ? "three in one plane" : "two parallel lines"));
}

}  // namespace

// The knot, point `<name>.knot` with coordinates `<name>.knot.x`, `.y`, `.z`, starting at `at` with
// the velocity of that expression (so a knot written as a body point of the kite moves with it).
void declare_bridles(ModelReader& r, const YAML::Node& node, ElementContext& /*ctx*/) {
  for (const ElementEntry& e :
       element_entries(r, node, "bridles", "bridle", bridle_keys(), "{lines, length, at, mass}")) {
    const std::vector<std::string> points = line_points(r, e);
    const std::vector<GiNaC::ex> lengths = line_lengths(r, e, points.size());
    if (!e.spec["at"])
      r.fail(e.key, fmt::format("expected 'at' (the knot's position at t = 0) in {}", e.what));
    const Vec3 at = r.vector_expr(e.spec["at"], model::kAll, "position of the knot of " + e.what);
    const Num3 k0 = initial_of(r, at, e.spec["at"], "the knot of " + e.what);
    Vec3 at_rate;
    for (size_t k = 0; k < 3; ++k) at_rate[k] = r.model().time_derivative(at[k]);
    const Num3 v0 = initial_of(r, at_rate, e.spec["at"], "the knot's velocity of " + e.what);
    std::vector<Num3> directions;
    for (size_t i = 0; i < points.size(); ++i) {
      const Num3 p0 =
          initial_of(r, r.model().find_point(points[i])->pos, e.spec["lines"][i], points[i]);
      const Num3 d{p0[0] - k0[0], p0[1] - k0[1], p0[2] - k0[2]};
      const double l0 = r.evaluate(lengths[i]).value_or(0.0);
      if (std::abs(norm(d) - l0) > 1e-9 * l0)
        r.fail(e.spec["at"],
               fmt::format("expected the knot of {} at its line lengths from the points at t = 0: "
                           "line {} to '{}' has length {:g}, the knot is {:.12g} away",
                           e.what, i + 1, points[i], l0, norm(d)));
      directions.push_back(d);
    }
    if (points.size() > 1) check_independent(r, e, directions);
    Vec3 pos;
    for (size_t k = 0; k < 3; ++k)
      pos[k] = r.add_coordinate(fmt::format("{}.knot.{}", e.name, "xyz"[k]), k0[k], v0[k], e.key).q;
    r.add_point(e.name + ".knot", pos, e.key);
  }
}

void lower_bridles(ModelReader& r, const YAML::Node& node, ElementContext& ctx) {
  Model& m = r.model();
  for (const auto& kv : node) {
    const ElementEntry e{kv.first, kv.second, kv.first.Scalar(),
                         "bridle '" + kv.first.Scalar() + "'"};
    const SourceLoc loc = r.source().at(e.key);
    const std::vector<std::string> points = line_points(r, e);
    const std::vector<GiNaC::ex> lengths = line_lengths(r, e, points.size());
    GiNaC::ex mass = 0;
    if (e.spec["mass"]) {
      mass = r.scalar_expr(e.spec["mass"], model::kParams, "mass of the knot of " + e.what);
      r.check_sign(mass, e.spec["mass"], false, "mass of the knot of " + e.what);
    }
    const std::string knot_name = e.name + ".knot";
    bool tethered = false;
    for (const Tether& t : ctx.tethers)
      tethered = tethered || t.nodes.front() == knot_name || t.nodes.back() == knot_name;
    if (mass.is_zero() && !tethered)
      r.fail(e.key, fmt::format("expected a tether ending at the knot '{}' or a positive 'mass' "
                                "in {}: a knot without mass has no dynamics of its own",
                                knot_name, e.what));
    if (!mass.is_zero()) m.particles.push_back(Particle{knot_name, mass, loc, true});

    const Vec3 knot = m.find_point(knot_name)->pos;
    ElementSummary summary{fmt::format("Bridle '{}': {} line{} to the knot '{}'", e.name,
                                       points.size(), points.size() == 1 ? "" : "s", knot_name),
                           {},
                           {}};
    for (size_t i = 0; i < points.size(); ++i) {
      const Vec3& p = m.find_point(points[i])->pos;
      GiNaC::ex sq = 0;
      for (size_t k = 0; k < 3; ++k) sq += GiNaC::pow(knot[k] - p[k], 2);
      const std::string line = fmt::format("{}.line{}", e.name, i + 1);
      m.constraints.push_back(NamedExpr{line, (sq - GiNaC::pow(lengths[i], 2)) / 2, loc});
      m.reactions.push_back(Reaction{fmt::format("{}.tension_{}", e.name, i + 1),
                                     m.constraints.size() - 1, lengths[i], loc});
      summary.equations.emplace_back("C_" + std::to_string(i + 1), m.constraints.back().expr);
    }
    summary.equations.emplace_back("m_knot", mass);
    std::string to;
    for (const std::string& p : points) to += (to.empty() ? "" : ", ") + p;
    summary.notes.push_back(
        fmt::format("lines to {}; massless; {}.tension_i = lambda_i * l_i (N)", to, e.name));
    m.element_summaries.push_back(std::move(summary));
  }
}

}  // namespace lagrange::elements
