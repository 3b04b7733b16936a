#include "elements/tether.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "model/model_reader.hpp"
#include "model/vec3_algebra.hpp"

namespace lagrange::elements {

ElementContext::ElementContext() = default;
ElementContext::~ElementContext() = default;

namespace {

using model::ModelReader;
using Num3 = std::array<double, 3>;

using model::add;
using model::dot3;
using model::scale;
using model::sub;
double norm(const Num3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}
Num3 lerp(const Num3& a, const Num3& b, double s) {
  return {a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])};
}

/// One end of a tether: a point name, a fixed or prescribed position, or (second end) free.
struct End {
  bool free = false;
  std::string point;  ///< a user point; empty for a position written in place
  Vec3 pos{0, 0, 0};
};

End read_end(ModelReader& r, const YAML::Node& node, bool may_be_free, const std::string& what) {
  End e;
  if (node.IsSequence()) {
    e.pos = r.vector_expr(node, model::kParams | model::kTime, what);
    return e;
  }
  const std::string name = r.scalar(node, what);
  if (name == "free") {
    if (!may_be_free)
      r.fail(node, fmt::format("expected a point or [x, y, z] for {}, got 'free' (only the "
                               "second end may be free)",
                               what));
    e.free = true;
    return e;
  }
  e.point = r.point_name(node, what);
  e.pos = r.model().find_point(e.point) ? r.model().find_point(e.point)->pos : e.pos;
  return e;
}

Num3 initial_position(ModelReader& r, const Vec3& pos, const YAML::Node& node,
                      const std::string& what) {
  Num3 x{};
  for (size_t k = 0; k < 3; ++k) {
    const auto v = r.initial_value(pos[k]);
    if (!v) r.fail(node, fmt::format("expected {} to have a finite position at t = 0", what));
    x[k] = *v;
  }
  return x;
}

/// Unit vector of gravity (down), or −z without gravity.
Num3 down_direction(ModelReader& r) {
  Num3 g{0, 0, -1};
  if (!r.model().gravity) return g;
  for (size_t k = 0; k < 3; ++k) {
    const auto v = r.evaluate((*r.model().gravity)[k]);
    if (!v) return Num3{0, 0, -1};
    g[k] = *v;
  }
  const double n = norm(g);
  if (!(n > 0)) return Num3{0, 0, -1};
  return {g[0] / n, g[1] / n, g[2] / n};
}

// Initial shape (docs/model-language.md, "Tethers"): a free end hangs straight along gravity; a
// slack tether between two ends starts as N equal segments of length ℓ/N, symmetric about the
// chord's midpoint and sagging along gravity (perpendicular to the chord), with slopes
// tan φᵢ = c uᵢ, uᵢ = 1 − (2i + 1)/N, that fall linearly along it as a parabola's do; c is found by
// bisection so that the segments span the chord. The segments then meet the constraints to
// rounding (antisymmetry closes the sag exactly), and no initial projection is needed. A taut
// tether is straight; one too slack for the profile (N odd, span < ℓ/N) falls back to the
// straight sag through the midpoint below.
std::vector<Num3> initial_shape(ModelReader& r, const Tether& t, const Num3& a, const Num3* b,
                                double length) {
  const size_t n = t.segments;
  std::vector<Num3> x(n + 1);
  const Num3 down = down_direction(r);
  if (b == nullptr) {
    for (size_t j = 0; j <= n; ++j)
      x[j] = lerp(a, {a[0] + length * down[0], a[1] + length * down[1], a[2] + length * down[2]},
                  static_cast<double>(j) / n);
    return x;
  }
  const Num3 chord{(*b)[0] - a[0], (*b)[1] - a[1], (*b)[2] - a[2]};
  const double span = norm(chord);
  for (size_t j = 0; j <= n; ++j) x[j] = lerp(a, *b, static_cast<double>(j) / n);
  if (span >= length || span == 0) return x;
  Num3 along{chord[0] / span, chord[1] / span, chord[2] / span};
  Num3 sag = down;  // the part of ĝ perpendicular to the chord
  const auto remove_along = [&] {
    const double d = sag[0] * along[0] + sag[1] * along[1] + sag[2] * along[2];
    for (size_t k = 0; k < 3; ++k) sag[k] -= d * along[k];
  };
  remove_along();
  if (norm(sag) < 1e-6) sag = std::abs(along[0]) < 0.9 ? Num3{1, 0, 0} : Num3{0, 1, 0};
  remove_along();
  const double s = norm(sag);
  for (auto& c : sag) c /= s;
  const double piece = length / static_cast<double>(n);
  const auto u = [&](size_t i) { return 1.0 - (2.0 * static_cast<double>(i) + 1.0) / n; };
  const auto reach = [&](double c) {  // the chordwise extent of the segments at slope factor c
    double sum = 0;
    for (size_t i = 0; i < n; ++i) sum += piece / std::sqrt(1 + c * c * u(i) * u(i));
    return sum;
  };
  double lo = 0, hi = 1;
  while (reach(hi) > span && hi < 1e12) hi *= 2;
  if (reach(hi) > span) {  // N odd and nearly no span: the middle segment alone is too long
    for (size_t j = 1; j < n; ++j) {
      const double depth = std::sqrt(std::max(0.0, length * length - span * span)) / 2;
      const double w = 1 - std::abs(2.0 * static_cast<double>(j) / n - 1);
      for (size_t k = 0; k < 3; ++k) x[j][k] += w * depth * sag[k];
    }
    return x;
  }
  for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
    const double mid = (lo + hi) / 2;
    (reach(mid) > span ? lo : hi) = mid;
  }
  const double c = (lo + hi) / 2, scale = span / reach(c);  // scale: 1 to rounding
  for (size_t i = 0; i < n; ++i) {
    const double g = 1 / std::sqrt(1 + c * c * u(i) * u(i));
    const double dx = piece * g * scale, dy = piece * c * u(i) * g;
    for (size_t k = 0; k < 3; ++k) x[i + 1][k] = x[i][k] + dx * along[k] + dy * sag[k];
  }
  x[n] = *b;
  return x;
}

GiNaC::ex required_positive(ModelReader& r, const YAML::Node& spec, const char* key,
                            const std::string& what, bool strict) {
  if (!spec[key]) r.fail(spec, fmt::format("expected '{}' in {}, got none", key, what));
  GiNaC::ex e = r.scalar_expr(spec[key], model::kParams, fmt::format("{} of {}", key, what));
  r.check_sign(e, spec[key], strict, fmt::format("{} of {}", key, what));
  return e;
}

bool depends_on_free_body(const Model& m, const Vec3& pos) {
  for (const Body& b : m.bodies) {
    if (!b.free) continue;
    for (const auto& e : pos) {
      for (const auto& s : b.r)
        if (e.has(s)) return true;
      for (const auto& s : b.R)
        if (e.has(s)) return true;
    }
  }
  return false;
}

// Whether a position depends on the state (a coordinate or a free body).
bool moves(const Model& m, const Vec3& pos) {
  for (const Coordinate& c : m.coordinates)
    for (const auto& e : pos)
      if (e.has(c.q)) return true;
  return depends_on_free_body(m, pos);
}

}  // namespace

void declare_tethers(ModelReader& r, const YAML::Node& node, ElementContext& ctx) {
  const std::vector<std::string> keys{"between",         "segments", "model",     "length",
                                      "mass_per_length", "diameter", "cd",        "drag",
                                      "air_density",     "damping",  "elasticity"};
  for (const ElementEntry& entry : element_entries(
           r, node, "tethers", "tether", keys, "{between, segments, length, mass_per_length, …}")) {
    Tether t;
    t.name = entry.name;
    t.node = entry.spec;
    const std::string& what = entry.what;
    const YAML::Node& spec = entry.spec;
    const YAML::Node& key = entry.key;
    const YAML::Node between = spec["between"];
    if (!between) r.fail(spec, fmt::format("expected 'between: [a, b]' in {}, got none", what));
    if (!between.IsSequence() || between.size() != 2)
      r.fail(between, fmt::format("expected two ends [a, b] for 'between' of {}, got {}", what,
                                  r.describe(between)));
    const End a = read_end(r, between[0], false, "the first end of " + what);
    const End b = read_end(r, between[1], true, "the second end of " + what);

    if (!spec["segments"]) r.fail(spec, fmt::format("expected 'segments' in {}, got none", what));
    const double nseg = r.number(spec["segments"], model::kParams, "segments of " + what);
    if (nseg < 1 || nseg > 1000 || nseg != std::floor(nseg))
      r.fail(spec["segments"],
             fmt::format("expected a whole number of segments from 1 to 1000 for {}, got {:g}",
                         what, nseg));
    t.segments = static_cast<size_t>(nseg);
    if (spec["model"]) {
      const std::string kind = r.scalar(spec["model"], "model of " + what);
      if (kind != "lumped" && kind != "full")
        r.fail(spec["model"], fmt::format("expected 'lumped' or 'full' for the model of {}, got "
                                          "'{}'",
                                          what, model::clip(kind)));
      t.full = kind == "full";
    }
    t.mass_per_length = required_positive(r, spec, "mass_per_length", what, true);
    if (spec["drag"]) {
      const std::string drag = r.scalar(spec["drag"], "drag of " + what);
      if (drag == "simple")
        t.drag = Tether::Drag::Simple;
      else if (drag == "fine")
        t.drag = Tether::Drag::Fine;
      else if (drag != "none")
        r.fail(spec["drag"], fmt::format("expected 'none', 'simple' or 'fine' for the drag of {}, "
                                         "got '{}'",
                                         what, model::clip(drag)));
    }
    if (t.drag != Tether::Drag::None || spec["diameter"])
      t.diameter = required_positive(r, spec, "diameter", what, true);
    if (spec["cd"]) t.cd = required_positive(r, spec, "cd", what, false);
    t.air_density = GiNaC::numeric(49, 40);  // 1.225 kg/m³, sea level (ISA)
    if (spec["air_density"]) {
      t.air_density = required_positive(r, spec, "air_density", what, false);
      r.warn_implausible(t.air_density, spec["air_density"], ModelReader::Quantity::AirDensity,
                         "the air density of " + what);
    }
    if (spec["damping"]) t.damping = required_positive(r, spec, "damping", what, false);
    if (const YAML::Node el = spec["elasticity"]) {
      const std::string of = "the elasticity of " + what;
      r.expect_map(el, of + " ({EA, damping})");
      r.check_keys(el, {"EA", "damping"}, of);
      Tether::Elasticity e;
      e.EA = required_positive(r, el, "EA", of, true);
      if (el["damping"]) e.damping = required_positive(r, el, "damping", of, false);
      t.elasticity = e;
    }

    // The length: a winch's coordinate, or a constant / ℓ(t) written here.
    const Winch* winch = nullptr;
    for (Winch& w : ctx.winches)
      if (w.tether == t.name) {
        if (winch != nullptr)
          r.fail(w.key,
                 fmt::format("expected one winch per tether, got a second one for {}", what));
        winch = &w;
        w.used = true;
      }
    double length0 = 0, rate0 = 0;  // ℓ and ℓ̇ at t = 0
    if (winch != nullptr) {
      if (spec["length"])
        r.fail(spec["length"],
               fmt::format("expected no 'length' in {}: winch '{}' sets it", what, winch->name));
      t.length = r.model().coordinates[winch->coordinate].q;
      t.length_coordinate = static_cast<int>(winch->coordinate);
      t.variable_length = true;
      length0 = winch->initial;
      rate0 = winch->rate;
    } else {
      if (!spec["length"]) r.fail(spec, fmt::format("expected 'length' in {}, got none", what));
      t.length = r.scalar_expr(spec["length"], model::kParams | model::kTime, "length of " + what);
      t.variable_length = t.length.has(r.model().t);
      const auto l0 = r.initial_value(t.length);
      if (!l0 || *l0 <= 0)
        r.fail(spec["length"], fmt::format("expected a positive length for {} at t = 0", what));
      length0 = *l0;
      if (t.variable_length) rate0 = r.initial_value(t.length.diff(r.model().t)).value_or(0.0);
    }
    if (t.variable_length &&
        (depends_on_free_body(r.model(), a.pos) || depends_on_free_body(r.model(), b.pos)))
      r.fail(between, fmt::format("expected ends of {} that are not points of free bodies: a "
                                  "tether of varying length is written through its kinetic "
                                  "energy, which may not use a free body's coordinates",
                                  what));

    // Nodes: the ends' points (or generated ones for written positions), coordinates between.
    const Num3 a0 = initial_position(r, a.pos, between[0], "the first end of " + what);
    Num3 b0{};
    if (!b.free) {
      b0 = initial_position(r, b.pos, between[1], "the second end of " + what);
      const double span = norm({b0[0] - a0[0], b0[1] - a0[1], b0[2] - a0[2]});
      if (!t.elasticity && span > length0 * (1 + 1e-9))
        r.fail(between, fmt::format("expected ends of {} at most its length {:g} apart at t = 0, "
                                    "got {:g} (an elastic tether may start stretched)",
                                    what, length0, span));
    }
    const std::vector<Num3> shape = initial_shape(r, t, a0, b.free ? nullptr : &b0, length0);
    const size_t n = t.segments;
    // A free end reeled at ℓ̇ starts with the segments growing at ℓ̇/N: the straight tether
    // stretches about its first end, ṙⱼ = (ℓ̇/ℓ)(rⱼ − r₀), so that Ċ = 0 holds with the file's rate
    // (docs/theory.md §4.6). Between two ends the initial projection finds the node velocities.
    const double stretch = b.free ? rate0 / length0 : 0.0;
    for (size_t j = 0; j <= n; ++j) {
      const std::string name = fmt::format("{}.node{}", t.name, j);
      const bool end = j == 0 || (j == n && !b.free);
      if (end) {
        const End& e = j == 0 ? a : b;
        t.nodes.push_back(e.point.empty() ? name : e.point);
        if (e.point.empty()) r.add_point(name, e.pos, between[j == 0 ? 0 : 1]);
        continue;
      }
      Vec3 pos;
      for (size_t k = 0; k < 3; ++k)
        pos[k] = r.add_coordinate(fmt::format("{}.{}", name, "xyz"[k]), shape[j][k],
                                  stretch * (shape[j][k] - a0[k]), key)
                     .q;
      r.add_point(name, pos, key);
      t.nodes.push_back(name);
    }
    if (n == 1 && !b.free && !moves(r.model(), a.pos) && !moves(r.model(), b.pos))
      r.fail(spec["segments"], fmt::format("expected a tether with a moving end or at least two "
                                           "segments, got {} with one segment between fixed "
                                           "ends",
                                           what));
    ctx.tethers.push_back(std::move(t));
  }
}

namespace {

// docs/theory.md §4.5–4.6: the material velocity of the tether at node j, for a tether reeled
// out at the first end with speed ℓ̇: v = ṙⱼ + ℓ̇ (1 − j/N) t̂, t̂ the unit tangent of the segment.
Vec3 material_velocity(const Model& m, const Vec3& pos, const GiNaC::ex& ldot,
                       const GiNaC::ex& frac, const Vec3& tangent) {
  Vec3 v;
  for (size_t k = 0; k < 3; ++k) v[k] = m.time_derivative(pos[k]) + ldot * (1 - frac) * tangent[k];
  return v;
}

// Kinetic and potential energy of a tether whose length changes (docs/theory.md §4.6): the
// tether and the reel form one control volume of constant mass, so the Euler–Lagrange
// equations of T and U hold without mass-flow corrections.
void add_variable_length_energy(ModelReader& r, const Tether& t) {
  Model& m = r.model();
  const size_t n = t.segments;
  const GiNaC::ex N = GiNaC::numeric(static_cast<int>(n));
  const GiNaC::ex ldot = m.time_derivative(t.length);
  const Vec3 g = m.gravity.value_or(Vec3{0, 0, 0});
  std::vector<Vec3> r_j;
  for (const auto& name : t.nodes) r_j.push_back(m.find_point(name)->pos);
  auto tangent = [&](size_t seg) { return scale(N / t.length, sub(r_j[seg], r_j[seg - 1])); };
  GiNaC::ex T = 0, U = 0;
  if (!t.full) {
    const GiNaC::ex mj = t.mass_per_length * t.length / (N + 1);
    for (size_t j = 0; j <= n; ++j) {
      const Vec3 v = material_velocity(m, r_j[j], ldot,
                                       GiNaC::numeric(static_cast<int>(j), static_cast<int>(n)),
                                       tangent(j == 0 ? 1 : j));
      T += mj / 2 * dot3(v, v);
      U -= mj * dot3(g, r_j[j]);
    }
  } else {
    const GiNaC::ex ms = t.mass_per_length * t.length / N;
    for (size_t j = 1; j <= n; ++j) {
      const Vec3 tj = tangent(j);
      const Vec3 va = material_velocity(
          m, r_j[j - 1], ldot, GiNaC::numeric(static_cast<int>(j - 1), static_cast<int>(n)), tj);
      const Vec3 vb = material_velocity(
          m, r_j[j], ldot, GiNaC::numeric(static_cast<int>(j), static_cast<int>(n)), tj);
      T += ms / 6 * (dot3(va, va) + dot3(vb, vb) + dot3(va, vb));
      U -= ms * dot3(g, scale(GiNaC::numeric(1, 2), add(r_j[j - 1], r_j[j])));
    }
  }
  m.kinetic += T;
  m.potential += U;
}

// Constant length: the lumped model is N + 1 particles of mass μℓ/(N + 1) (seed 000, "Tether
// Models"); the full model's T = (mₛ/6)(|ṙₐ|² + |ṙ_b|² + ṙₐ·ṙ_b) is, identically, a particle mₛ at
// the segment's midpoint plus a gravity-free particle mₛ/12 at d = r_b − rₐ (docs/theory.md §4.5).
void add_constant_length_masses(ModelReader& r, const Tether& t) {
  Model& m = r.model();
  const size_t n = t.segments;
  const GiNaC::ex N = GiNaC::numeric(static_cast<int>(n));
  const SourceLoc loc = r.source().at(t.node);
  if (!t.full) {
    const GiNaC::ex mj = t.mass_per_length * t.length / (N + 1);
    for (const auto& name : t.nodes) m.particles.push_back(Particle{name, mj, loc, true});
    return;
  }
  const GiNaC::ex ms = t.mass_per_length * t.length / N;
  for (size_t j = 1; j <= n; ++j) {
    const Vec3 a = m.find_point(t.nodes[j - 1])->pos, b = m.find_point(t.nodes[j])->pos;
    const std::string mid = fmt::format("{}.mid{}", t.name, j);
    const std::string span = fmt::format("{}.span{}", t.name, j);
    r.add_point(mid, scale(GiNaC::numeric(1, 2), add(a, b)), t.node);
    r.add_point(span, sub(b, a), t.node);
    m.particles.push_back(Particle{mid, ms, loc, true});
    m.particles.push_back(Particle{span, ms / 12, loc, false});
  }
}

// docs/theory.md §4.5: Cⱼ = ½(|rⱼ − rⱼ₋₁|² − (ℓ/N)²); the segment's tension is λⱼ ℓ/N.
// Returns the index of segment 1's constraint.
size_t add_length_constraints(Model& m, const Tether& t, const SourceLoc& loc) {
  const size_t first = m.constraints.size();
  const GiNaC::ex seg = t.length / GiNaC::numeric(static_cast<int>(t.segments));
  for (size_t j = 1; j <= t.segments; ++j) {
    const Vec3 d = sub(m.find_point(t.nodes[j])->pos, m.find_point(t.nodes[j - 1])->pos);
    m.constraints.push_back(
        NamedExpr{fmt::format("{}.segment{}", t.name, j), (dot3(d, d) - seg * seg) / 2, loc});
    m.reactions.push_back(
        Reaction{fmt::format("{}.tension_{}", t.name, j), m.constraints.size() - 1, seg, loc});
    if (j == 1)
      m.reactions.push_back(
          Reaction{t.name + ".tension_ground", m.constraints.size() - 1, seg, loc});
  }
  return first;
}

// docs/theory.md §4.11: the force a fixed first end's support carries, −S from node 0's
// Euler–Lagrange equation: Q₀ + λ₁ (r₁ − r₀) (or the elastic pull) + m₀ g for the lumped model,
// + (mₛ/2) g − (mₛ/6) r̈₁ for the full one. Only for a constant length at a support at rest.
void add_anchor_load(Model& m, const Tether& t, const Vec3& node_force,
                     std::optional<size_t> segment1, const SourceLoc& loc) {
  const Vec3& r0 = m.find_point(t.nodes[0])->pos;
  const Vec3& r1 = m.find_point(t.nodes[1])->pos;
  for (const auto& x : r0)
    if (!m.time_derivative(x).is_zero()) return;
  const GiNaC::ex N = GiNaC::numeric(static_cast<int>(t.segments));
  const Vec3 g = m.gravity.value_or(Vec3{0, 0, 0});
  Load load{t.name + ".load_ground", {}, loc};
  for (size_t k = 0; k < 3; ++k) {
    LoadPart part{node_force[k], {}};
    if (t.full) {
      const GiNaC::ex ms = t.mass_per_length * t.length / N;
      part.expr += ms / 2 * g[k] - ms / 6 * m.time_derivative(m.time_derivative(r1[k]));
    } else {
      part.expr += t.mass_per_length * t.length / (N + 1) * g[k];
    }
    if (segment1) part.multipliers.emplace_back(*segment1, r1[k] - r0[k]);
    load.parts.push_back(std::move(part));
  }
  m.loads.push_back(std::move(load));
}

// docs/theory.md §4.10: Q_ℓ on the winch's coordinate; strain, tension and elastic energy as
// outputs. The segments' pulls are returned, to join the node forces (virtual work, §4.2).
ElasticSegments add_elastic_segments(Model& m, const Tether& t, const SourceLoc& loc) {
  ElasticSegments el = elastic_segments(m, t);
  if (t.length_coordinate >= 0)
    m.generalized_forces[static_cast<size_t>(t.length_coordinate)] += el.length_force;
  for (size_t j = 1; j <= t.segments; ++j) {
    m.outputs.push_back(NamedExpr{fmt::format("{}.strain_{}", t.name, j), el.strain[j - 1], loc});
    m.outputs.push_back(NamedExpr{fmt::format("{}.tension_{}", t.name, j), el.tension[j - 1], loc});
  }
  m.outputs.push_back(NamedExpr{t.name + ".tension_ground", el.tension[0], loc});
  m.outputs.push_back(NamedExpr{t.name + ".elastic_energy", el.energy, loc});
  return el;
}

}  // namespace

void lower_tethers(ModelReader& r, const YAML::Node& /*node*/, ElementContext& ctx) {
  Model& m = r.model();
  for (const Tether& t : ctx.tethers) {
    const size_t n = t.segments;
    const GiNaC::ex seg = t.length / GiNaC::numeric(static_cast<int>(n));
    const SourceLoc loc = r.source().at(t.node);
    if (t.variable_length)
      add_variable_length_energy(r, t);
    else
      add_constant_length_masses(r, t);
    std::vector<Vec3> force = tether_drag(m, t, ctx.wind ? &*ctx.wind : nullptr);
    std::optional<ElasticSegments> elastic;
    std::optional<size_t> segment1;
    if (t.elasticity)
      elastic = add_elastic_segments(m, t, loc);
    else
      segment1 = add_length_constraints(m, t, loc);
    GiNaC::ex power = 0;  // of drag and node damping: Σ Fⱼ·ṙⱼ (not of the elastic segments)
    for (size_t j = 0; j <= n; ++j) {
      const Vec3& pos = m.find_point(t.nodes[j])->pos;
      const bool own = m.coordinate_index(fmt::format("{}.node{}.x", t.name, j)) >= 0;
      if (!t.damping.is_zero() && own) {
        const GiNaC::ex c = t.damping * seg;
        for (size_t k = 0; k < 3; ++k) force[j][k] -= c * m.time_derivative(pos[k]);
      }
      for (size_t k = 0; k < 3; ++k) power += force[j][k] * m.time_derivative(pos[k]);
      const Vec3 total = elastic ? model::add(force[j], elastic->force[j]) : force[j];
      bool any = false;
      for (const auto& f : total) any = any || !f.is_zero();
      if (any) m.forces.push_back(PointForce{t.nodes[j], total, loc});
      if (j == 0 && !t.variable_length) add_anchor_load(m, t, total, segment1, loc);
    }
    ElementSummary summary{fmt::format("Tether '{}': {} {}segments, {} model{}", t.name, n,
                                       t.elasticity ? "elastic " : "", t.full ? "full" : "lumped",
                                       t.variable_length ? ", varying length" : ""),
                           {},
                           {}};
    summary.notes.push_back(fmt::format("nodes r_0 = {}, r_{} = {}; segment 1 of {} shown",
                                        t.nodes[0], n, t.nodes[n], n));
    summary.equations.emplace_back("l_s", seg);
    summary.equations.emplace_back(
        t.full ? "m_segment" : "m_node",
        t.mass_per_length * t.length / GiNaC::numeric(static_cast<int>(t.full ? n : n + 1)));
    if (elastic) {
      summary.equations.emplace_back("eps_1", elastic->strain[0]);
      summary.equations.emplace_back("T_1", elastic->tension[0]);
      if (t.length_coordinate >= 0)
        summary.equations.emplace_back(
            "Q_" + m.coordinates[static_cast<size_t>(t.length_coordinate)].name,
            elastic->length_force);
    } else {
      summary.equations.emplace_back("C_1", m.constraints[m.constraints.size() - n].expr);
    }
    for (size_t k = 0; k < 3; ++k)
      if (!force[0][k].is_zero() || !force[1][k].is_zero())
        summary.equations.emplace_back(fmt::format("F_node1.{}", "xyz"[k]), force[1][k]);
    summary.notes.push_back(fmt::format(
        "{}.tension_j = {} (N); drag: {}", t.name,
        t.elasticity ? "EA eps+ + g max(D eps', -EA eps+), elastic (docs/theory.md §4.10)"
                     : "lambda_j * l_s",
        t.drag == Tether::Drag::None     ? "none"
        : t.drag == Tether::Drag::Simple ? "simple"
                                         : "fine"));
    if (t.variable_length)
      summary.notes.push_back(
          "T and U use the material velocity r_j' + l' (1 - j/N) t_j "
          "(docs/theory.md §4.6)");
    m.element_summaries.push_back(std::move(summary));
    m.outputs.push_back(NamedExpr{t.name + ".length", t.length, loc});
    m.outputs.push_back(NamedExpr{t.name + ".mass", t.mass_per_length * t.length, loc});
    if (!power.is_zero()) m.outputs.push_back(NamedExpr{t.name + ".drag_power", power, loc});
  }
}

}  // namespace lagrange::elements
