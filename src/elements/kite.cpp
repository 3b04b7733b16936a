// `kites:` (docs/model-language.md, "Kites"; docs/theory.md §4.7): a point-mass kite on a point
// or a rigid kite on a free body, lowered into a point force (and a body-frame torque).

#include "elements/kite.hpp"

#include <fmt/format.h>

#include <cctype>
#include <sstream>

#include "elements/tether.hpp"
#include "model/model_reader.hpp"

namespace lagrange::elements {

using model::ModelReader;
using LocalNames = ModelReader::LocalNames;

namespace {

/// One kite as read in phase 1: its key, spec and what it flies on.
struct KiteSpec {
  std::string name;
  YAML::Node key, spec;
  const KitePreset* preset = nullptr;
};

/// The names kite expressions may use, as symbols; lowering substitutes their expressions.
struct KiteSymbols {
  GiNaC::symbol alpha{"alpha"}, beta{"beta"}, airspeed{"airspeed"}, phat{"phat"}, qhat{"qhat"},
      rhat{"rhat"}, height{"height"}, azimuth{"azimuth"}, elevation{"elevation"},
      heading{"heading"}, aileron{"aileron"}, elevator{"elevator"}, rudder{"rudder"}, cl{"CL"};
};

const std::vector<std::string>& kite_keys() {
  static const std::vector<std::string> keys = {
      "point", "body", "preset",       "mass",        "area",   "span",
      "chord", "cd0",  "aspect_ratio", "air_density", "tether", "CL",
      "CD",    "roll", "aileron",      "elevator",    "rudder", "coefficients"};
  return keys;
}

/// A control law or coefficient: an expression of t, the state and the kite's names. A tension
/// column (`main.tension_ground`) is a constraint force λ·ℓ, known only once the accelerations
/// are solved with the forces already in place, so a law cannot use it (docs/model-language.md,
/// "Kites").
GiNaC::ex law(ModelReader& r, const YAML::Node& node, const std::string& what,
              const LocalNames& names) {
  if (node.IsScalar()) {
    const std::string& text = node.Scalar();
    auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (const Reaction& reaction : r.model().reactions) {
      const std::string& name = reaction.name;
      for (size_t at = text.find(name); at != std::string::npos; at = text.find(name, at + 1)) {
        const size_t end = at + name.size();
        if ((at > 0 && (word(text[at - 1]) || text[at - 1] == '.')) ||
            (end < text.size() && word(text[end])))
          continue;
        r.fail(node, fmt::format("expected an expression of t and the state in {}, got the "
                                 "constraint force '{}': it is known only after the "
                                 "accelerations are solved with the kite's forces in place. "
                                 "Feed back the state instead (positions, speeds, airspeed, "
                                 "alpha, a winch's der(reeled_out), …)",
                                 what, name));
      }
    }
  }
  return r.scalar_expr(node, model::kAll, what, &names);
}

GiNaC::ex positive(ModelReader& r, const KiteSpec& k, const char* key, bool strict,
                   const GiNaC::ex* fallback) {
  const std::string what = fmt::format("{} of kite '{}'", key, k.name);
  if (!k.spec[key]) {
    if (fallback != nullptr) return *fallback;
    r.fail(k.key, fmt::format("expected '{}' in kite '{}'{}, got none", key, k.name,
                              k.preset ? "" : " (or a preset)"));
  }
  GiNaC::ex e = r.scalar_expr(k.spec[key], model::kParams, what);
  r.check_sign(e, k.spec[key], strict, what);
  return e;
}

/// The tether whose second end is `point`, or the one named by `tether:`.
const Tether* attached_tether(ModelReader& r, const KiteSpec& k, const std::string& point,
                              const ElementContext& ctx) {
  if (k.spec["tether"]) {
    const std::string name = r.scalar(k.spec["tether"], "tether of kite " + k.name);
    for (const Tether& t : ctx.tethers)
      if (t.name == name) return &t;
    std::string names;
    for (const Tether& t : ctx.tethers) names += (names.empty() ? "" : ", ") + t.name;
    r.fail(k.spec["tether"],
           fmt::format("expected the name of a tether for kite '{}', got '{}' "
                       "(tethers: {})",
                       k.name, model::clip(name), names.empty() ? "none" : names));
  }
  for (const Tether& t : ctx.tethers)
    if (t.nodes.back() == point) return &t;
  return nullptr;
}

/// Kinematic names shared by point-mass and rigid kites: height, azimuth, elevation, heading of
/// the kite at `pos` (velocity `vel`) seen from the ground end `ground`, in the wind frame.
void add_kinematics(const ElementContext& ctx, const Vec3& pos, const Vec3& vel, const Vec3& ground,
                    const KiteSymbols& s, GiNaC::exmap& values) {
  const Wind frame = ctx.wind.value_or(Wind{});
  const Vec3 x = frame.direction, up = frame.up, y = cross3(up, x);
  const Vec3 d = minus(pos, ground);
  const GiNaC::ex dx = dot_product(d, x), dy = dot_product(d, y), dz = dot_product(d, up);
  values[s.height] = dot_product(pos, up);
  values[s.azimuth] = GiNaC::atan2(dy, dx);
  values[s.elevation] = GiNaC::atan2(dz, GiNaC::sqrt(dx * dx + dy * dy));
  const Vec3 side = cross3(up, d);
  const Vec3 e_phi = scaled(1 / length3(side), side);
  const Vec3 e_theta = scaled(1 / length3(d), cross3(d, e_phi));
  values[s.heading] = GiNaC::atan2(dot_product(vel, e_phi), dot_product(vel, e_theta));
}

GiNaC::ex air_density(ModelReader& r, const KiteSpec& k, const GiNaC::ex& height) {
  if (!k.spec["air_density"]) return GiNaC::numeric(49, 40);
  const YAML::Node& n = k.spec["air_density"];
  if (n.IsScalar() && n.Scalar() == "isa") return isa_density(height);
  GiNaC::ex rho = r.scalar_expr(n, model::kParams, "air density of kite " + k.name + " (or isa)");
  r.check_sign(rho, n, false, "air density of kite " + k.name);  // 0: aerodynamics off
  r.warn_implausible(rho, n, ModelReader::Quantity::AirDensity,
                     "the air density of kite '" + k.name + "'");
  return rho;
}

Vec3 apparent_velocity(const Model& m, const ElementContext& ctx, const Vec3& pos) {
  Vec3 v;
  for (size_t i = 0; i < 3; ++i) v[i] = m.time_derivative(pos[i]);
  if (ctx.wind) v = minus(v, ctx.wind->at(pos));
  return v;
}

/// What both kinds of kite hand to the common outputs.
struct KiteLoads {
  Vec3 force;
  GiNaC::ex power, cl, cd, q_area;  ///< F, its power F·ṙ (+ M·ω), C_L, C_D and ½ρS|v_a|²
};

// The kite's columns, and a warning when it flies below the ground of its wind profile: height
// 0 (the roughness length z0 for the logarithmic profile, where its wind falls to zero).
void add_outputs(Model& m, const ElementContext& ctx, const std::string& name, const KiteLoads& l,
                 const GiNaC::exmap& values, const KiteSymbols& s, const SourceLoc& loc) {
  auto out = [&](const std::string& col, const GiNaC::ex& e) {
    m.outputs.push_back(NamedExpr{name + "." + col, e, loc});
  };
  out("airspeed", values.at(s.airspeed));
  out("CL", l.cl);
  out("CD", l.cd);
  out("lift", l.q_area * l.cl);
  out("drag", l.q_area * l.cd);
  out("power", l.power);
  out("azimuth", values.at(s.azimuth));
  out("elevation", values.at(s.elevation));
  out("heading", values.at(s.heading));
  out("height", values.at(s.height));
  const bool log = ctx.wind && ctx.wind->profile == Wind::Profile::Logarithmic;
  std::ostringstream ground;
  ground << (log ? ctx.wind->roughness : GiNaC::ex(0));
  m.warn_when.push_back(StopSpec{
      fmt::format("kite '{}' flies below the ground of its wind profile ({}): the wind and the "
                  "tether's shape there are not physical",
                  name, log ? "the roughness length z0" : "height 0"),
      fmt::format("{}.height < {}", name, ground.str()), loc});
}

// Point-mass kite (awebox three_dof_kite.py, docs/theory.md §4.7): F = ½ρS|v_a|² (C_L ê_L −
// C_D v̂_a), ê_L from the roll ψ about v_a, measured from the plane of the tether and v_a.
void lower_point_mass(ModelReader& r, const KiteSpec& k, const ElementContext& ctx) {
  Model& m = r.model();
  const SourceLoc loc = r.source().at(k.key);
  const std::string point = r.point_name(k.spec["point"], "point of kite " + k.name);
  const Vec3 pos = m.find_point(point)->pos;
  const Tether* tether = attached_tether(r, k, point, ctx);
  if (tether == nullptr)
    r.fail(k.spec["point"], fmt::format("expected a tether ending at point '{}' (its second end) "
                                        "for kite '{}': the roll angle is measured from the plane "
                                        "of the tether and the airspeed",
                                        point, k.name));
  const Vec3 before = m.find_point(tether->nodes[tether->nodes.size() - 2])->pos;
  const Vec3 ground = m.find_point(tether->nodes.front())->pos;

  const GiNaC::ex* preset_mass = k.preset ? &k.preset->mass : nullptr;
  const GiNaC::ex mass = positive(r, k, "mass", false, preset_mass);
  const GiNaC::ex area = positive(r, k, "area", true, k.preset ? &k.preset->area : nullptr);
  for (const char* key : {"body", "aileron", "elevator", "rudder", "coefficients", "chord"})
    if (k.spec[key])
      r.fail(k.spec[key], fmt::format("expected no '{}' in point-mass kite '{}' (it belongs to a "
                                      "rigid kite on a body)",
                                      key, k.name));

  KiteSymbols s;
  LocalNames names = {{"airspeed", s.airspeed},
                      {"height", s.height},
                      {"azimuth", s.azimuth},
                      {"elevation", s.elevation},
                      {"heading", s.heading}};
  const std::string what = "kite " + k.name;
  if (!k.spec["CL"]) r.fail(k.key, fmt::format("expected 'CL' (lift coefficient) in {}", what));
  const GiNaC::ex cl = law(r, k.spec["CL"], "CL of " + what, names);
  const GiNaC::ex roll = k.spec["roll"] ? law(r, k.spec["roll"], "roll of " + what, names) : 0;
  names["CL"] = s.cl;
  GiNaC::ex cd;
  if (k.spec["CD"]) {
    cd = law(r, k.spec["CD"], "CD of " + what, names);
  } else {
    const GiNaC::ex cd0 = positive(r, k, "cd0", false, k.preset ? &k.preset->cd0 : nullptr);
    GiNaC::ex ar;
    if (k.spec["aspect_ratio"] || k.preset || !k.spec["span"]) {
      const GiNaC::ex* fallback = k.preset ? &k.preset->aspect_ratio : nullptr;
      ar = positive(r, k, "aspect_ratio", true, fallback);
    } else {
      const GiNaC::ex span = positive(r, k, "span", true, nullptr);
      ar = span * span / area;
    }
    cd = cd0 + GiNaC::pow(s.cl, 2) / (GiNaC::Pi * ar);
  }

  GiNaC::exmap values;
  const Vec3 va = apparent_velocity(m, ctx, pos);
  Vec3 vel;
  for (size_t i = 0; i < 3; ++i) vel[i] = m.time_derivative(pos[i]);
  add_kinematics(ctx, pos, vel, ground, s, values);
  values[s.airspeed] = length3(va);
  const GiNaC::ex rho = air_density(r, k, s.height);
  const GiNaC::ex cd_of_cl = cd.subs(GiNaC::exmap{{s.cl, cl}});
  const GiNaC::ex q_area = rho * area * GiNaC::pow(s.airspeed, 2) / 2;
  const Vec3 lift_dir = point_mass_lift_direction(va, minus(pos, before), roll);

  KiteLoads loads;
  loads.q_area = q_area.subs(values);
  loads.cl = cl.subs(values);
  loads.cd = cd_of_cl.subs(values);
  const GiNaC::ex lift = loads.q_area * loads.cl,
                  drag_per_speed = loads.q_area * loads.cd / length3(va);
  for (size_t i = 0; i < 3; ++i)
    loads.force[i] = lift * lift_dir[i].subs(values) - drag_per_speed * va[i];
  loads.power = dot_product(loads.force, vel);

  if (!mass.is_zero()) m.particles.push_back(Particle{point, mass, loc, true});
  m.forces.push_back(PointForce{point, loads.force, loc});
  add_outputs(m, ctx, k.name, loads, values, s, loc);
  m.outputs.push_back(NamedExpr{k.name + ".roll", roll.subs(values), loc});

  ElementSummary summary{
      fmt::format("Kite '{}': point mass at '{}', tether '{}'{}", k.name, point, tether->name,
                  k.preset ? ", preset " + k.preset->name : std::string()),
      {},
      {}};
  summary.equations.emplace_back("m", mass);
  summary.equations.emplace_back("S", area);
  summary.equations.emplace_back("rho", rho);
  summary.equations.emplace_back("CL", cl);
  summary.equations.emplace_back("CD", cd);
  summary.equations.emplace_back("psi", roll);
  summary.notes.push_back(
      "F = rho/2 S |v_a|^2 (CL e_L - CD v_a/|v_a|), v_a = r' - w(r); e_L = cos(psi) e_n - "
      "sin(psi) e_0, e_0 = t x u_a/|t x u_a|, e_n = u_a/|u_a| x e_0, u_a = -v_a, t = the last "
      "tether segment");
  if (k.preset) summary.notes.push_back("data: " + k.preset->source);
  m.element_summaries.push_back(std::move(summary));
}

const Body& free_body(ModelReader& r, const KiteSpec& k) {
  const std::string name = r.scalar(k.spec["body"], "body of kite " + k.name);
  const Body* body = r.model().find_body(name);
  if (body == nullptr || !body->free) {
    std::string names;
    for (const Body& b : r.model().bodies)
      if (b.free) names += (names.empty() ? "" : ", ") + b.name;
    r.fail(k.spec["body"], fmt::format("expected the name of a free body (frame: free) for kite "
                                       "'{}', got '{}' (free bodies: {})",
                                       k.name, model::clip(name), names.empty() ? "none" : names));
  }
  return *body;
}

// Rigid kite (docs/theory.md §4.7, awebox six_dof_kite.py): v_a in body axes gives α, β; the
// coefficients give F_b = q S (C_X, C_Y, C_Z) at the centre of mass and M_b = q S (b C_l, c C_m,
// b C_n) about it. With CL and CD instead of C_X, C_Z: F_b = q S (C_L ê_L − C_D v̂_a + C_Y ŷ_b).
void lower_rigid(ModelReader& r, const KiteSpec& k, const ElementContext& ctx) {
  Model& m = r.model();
  const SourceLoc loc = r.source().at(k.key);
  const Body& body = free_body(r, k);
  const std::string what = "kite " + k.name;
  if (k.spec["mass"] || k.spec["roll"] || k.spec["CL"] || k.spec["CD"])
    r.fail(k.spec["mass"]   ? k.spec["mass"]
           : k.spec["roll"] ? k.spec["roll"]
           : k.spec["CL"]   ? k.spec["CL"]
                            : k.spec["CD"],
           fmt::format("expected no 'mass', 'roll', 'CL' or 'CD' in rigid kite '{}': the body "
                       "carries its mass, and coefficients go under 'coefficients'",
                       k.name));
  const GiNaC::ex area = positive(r, k, "area", true, k.preset ? &k.preset->area : nullptr);
  const GiNaC::ex span = positive(r, k, "span", true, k.preset ? &k.preset->span : nullptr);
  const GiNaC::ex default_chord = area / span;
  const GiNaC::ex chord = positive(r, k, "chord", true, &default_chord);

  const std::string cg_name = k.name + ".cg";
  r.add_point(cg_name, body.world_point(body.com), k.key);
  const Vec3 pos = m.find_point(cg_name)->pos;
  Vec3 vel;
  for (size_t i = 0; i < 3; ++i) vel[i] = m.time_derivative(pos[i]);
  const Vec3 va = apparent_velocity(m, ctx, pos);
  const Mat3 R = body.rot();
  Vec3 vb;  // Rᵀ v_a
  for (size_t i = 0; i < 3; ++i) vb[i] = R[0][i] * va[0] + R[1][i] * va[1] + R[2][i] * va[2];

  KiteSymbols s;
  GiNaC::exmap values;
  // The ground end: of the tether named, or of one ending at a point of the body (or the origin).
  const Tether* tether = k.spec["tether"] ? attached_tether(r, k, "", ctx) : nullptr;
  for (const Tether& t : ctx.tethers)
    if (tether == nullptr && t.nodes.back().rfind(body.name + ".", 0) == 0) tether = &t;
  const Vec3 ground = tether ? m.find_point(tether->nodes.front())->pos : Vec3{0, 0, 0};
  add_kinematics(ctx, pos, vel, ground, s, values);
  const FlowAngles flow = flow_angles(vb);
  values[s.alpha] = flow.alpha;
  values[s.beta] = flow.beta;
  values[s.airspeed] = flow.airspeed;
  values[s.phat] = body.w[0] * span / (2 * flow.airspeed);
  values[s.qhat] = body.w[1] * chord / (2 * flow.airspeed);
  values[s.rhat] = body.w[2] * span / (2 * flow.airspeed);

  LocalNames names = {{"alpha", s.alpha},    {"beta", s.beta},       {"airspeed", s.airspeed},
                      {"phat", s.phat},      {"qhat", s.qhat},       {"rhat", s.rhat},
                      {"height", s.height},  {"azimuth", s.azimuth}, {"elevation", s.elevation},
                      {"heading", s.heading}};
  for (const char* key : {"aileron", "elevator", "rudder"}) {
    const GiNaC::symbol& sym = key[0] == 'a' ? s.aileron : key[0] == 'e' ? s.elevator : s.rudder;
    values[sym] =
        k.spec[key]
            ? law(r, k.spec[key], fmt::format("{} deflection of {}", key, what), names).subs(values)
            : GiNaC::ex(0);
  }
  names["aileron"] = s.aileron;
  names["elevator"] = s.elevator;
  names["rudder"] = s.rudder;

  // Coefficients: the preset's tables, each replaced by what the file gives.
  const AeroInputs inputs{s.alpha, s.beta, s.phat, s.qhat, s.rhat, s.aileron, s.elevator, s.rudder};
  const std::array<const char*, 6> body_keys = {"CX", "CY", "CZ", "Cl", "Cm", "Cn"};
  std::map<std::string, GiNaC::ex> coeff;
  if (k.preset)
    for (size_t i = 0; i < 6; ++i) coeff[body_keys[i]] = k.preset->coefficients[i].evaluate(inputs);
  const YAML::Node cs = k.spec["coefficients"];
  if (cs) {
    r.expect_map(cs, "coefficients of " + what + " ({CX, CY, CZ, Cl, Cm, Cn} or CL, CD)");
    r.check_keys(cs, {"CX", "CY", "CZ", "Cl", "Cm", "Cn", "CL", "CD"}, "coefficients of " + what);
    for (const auto& kv : cs) {
      const std::string key = kv.first.Scalar();
      coeff[key] = law(r, kv.second,
                       fmt::format("{} of {} (an expression of alpha, beta, …)", key, what), names);
    }
  }
  const bool wind_axes = coeff.count("CL") || coeff.count("CD");
  if (wind_axes) {
    coeff.erase("CX");
    coeff.erase("CZ");
  }
  for (const char* key :
       wind_axes ? std::array<const char*, 6>{"CL", "CD", "CY", "Cl", "Cm", "Cn"} : body_keys)
    if (!coeff.count(key))
      r.fail(cs ? cs : k.key, fmt::format("expected '{}' under 'coefficients' of {} (or a "
                                          "preset)",
                                          key, what));

  const GiNaC::ex rho = air_density(r, k, s.height);
  const GiNaC::ex q_area = rho * area * GiNaC::pow(s.airspeed, 2) / 2;
  // Wind-axis unit vectors in body axes: v̂ along v_a, ê_L = (ŷ_b × v̂)/|ŷ_b × v̂| (up at α = 0).
  const Vec3 vhat{GiNaC::cos(s.alpha) * GiNaC::cos(s.beta), GiNaC::sin(s.beta),
                  GiNaC::sin(s.alpha) * GiNaC::cos(s.beta)};
  const Vec3 lift_dir{GiNaC::sin(s.alpha), 0, -GiNaC::cos(s.alpha)};
  Vec3 cf;  // force coefficients in body axes
  if (wind_axes) {
    for (size_t i = 0; i < 3; ++i) cf[i] = coeff["CL"] * lift_dir[i] - coeff["CD"] * vhat[i];
    cf[1] += coeff["CY"];
  } else {
    cf = {coeff["CX"], coeff["CY"], coeff["CZ"]};
  }
  const Vec3 fb = scaled(q_area, cf);
  const Vec3 mb{q_area * span * coeff["Cl"], q_area * chord * coeff["Cm"],
                q_area * span * coeff["Cn"]};
  Vec3 fb_state, mb_state, force;
  for (size_t i = 0; i < 3; ++i) {
    fb_state[i] = fb[i].subs(values);
    mb_state[i] = mb[i].subs(values);
  }
  for (size_t i = 0; i < 3; ++i)
    force[i] = R[i][0] * fb_state[0] + R[i][1] * fb_state[1] + R[i][2] * fb_state[2];

  KiteLoads loads;
  loads.force = force;
  loads.q_area = q_area.subs(values);
  loads.cl = dot_product(cf, lift_dir).subs(values);
  loads.cd = (-dot_product(cf, vhat)).subs(values);
  loads.power = dot_product(force, vel) + mb_state[0] * body.w[0] + mb_state[1] * body.w[1] +
                mb_state[2] * body.w[2];
  m.forces.push_back(PointForce{cg_name, force, loc});
  m.torques.push_back(BodyTorque{body.name, mb_state, true, loc});
  add_outputs(m, ctx, k.name, loads, values, s, loc);
  m.outputs.push_back(NamedExpr{k.name + ".alpha", flow.alpha, loc});
  m.outputs.push_back(NamedExpr{k.name + ".beta", flow.beta, loc});

  ElementSummary summary{fmt::format("Kite '{}': rigid body '{}'{}", k.name, body.name,
                                     k.preset ? ", preset " + k.preset->name : std::string()),
                         {},
                         {}};
  summary.equations.emplace_back("S", area);
  summary.equations.emplace_back("b", span);
  summary.equations.emplace_back("c", chord);
  summary.equations.emplace_back("rho", rho);
  for (const char* key :
       wind_axes ? std::array<const char*, 6>{"CL", "CD", "CY", "Cl", "Cm", "Cn"} : body_keys)
    summary.equations.emplace_back(key, coeff[key]);
  for (const auto& sym : {s.aileron, s.elevator, s.rudder})
    if (!values[sym].is_zero()) summary.equations.emplace_back(sym.get_name(), values[sym]);
  summary.notes.push_back(
      "body axes x forward, y right, z down; v_b = R^T (r_cg' - w); alpha = atan2(w_b, u_b), "
      "beta = asin(v_b/|v_a|); phat = p b/(2|v_a|), qhat = q c/(2|v_a|), rhat = r b/(2|v_a|)");
  summary.notes.push_back(wind_axes ? "F_b = rho/2 S |v_a|^2 (CL e_L - CD v_a/|v_a| + CY y_b)"
                                    : "F_b = rho/2 S |v_a|^2 (CX, CY, CZ) at the centre of mass");
  summary.notes.push_back("M_b = rho/2 S |v_a|^2 (b Cl, c Cm, b Cn) about the centre of mass");
  if (k.preset) summary.notes.push_back("data: " + k.preset->source);
  m.element_summaries.push_back(std::move(summary));
}

}  // namespace

void declare_kites(ModelReader& r, const YAML::Node& node, ElementContext& /*ctx*/) {
  r.expect_map(node, "kites (a map name: {point or body, area, CL, …})");
  r.check_keys(node, {}, "kites");
  for (const auto& kv : node) {
    r.declare_element(kv.first);
    const std::string what = fmt::format("kite '{}'", kv.first.Scalar());
    r.expect_map(kv.second, what + " (a map {point or body, preset, area, …})");
    r.check_keys(kv.second, kite_keys(), what);
    const bool on_point = bool(kv.second["point"]), on_body = bool(kv.second["body"]);
    if (on_point == on_body)
      r.fail(kv.first, fmt::format("expected exactly one of 'point' (a point-mass kite) or 'body' "
                                   "(a rigid kite) in {}, got {}",
                                   what, on_point ? "both" : "neither"));
    if (kv.second["preset"]) {
      const std::string p = r.scalar(kv.second["preset"], "preset of " + what);
      if (find_kite_preset(p) == nullptr)
        r.fail(kv.second["preset"], fmt::format("expected a kite preset ({}) for {}, got '{}'",
                                                kite_preset_names(), what, model::clip(p)));
    }
  }
}

void lower_kites(ModelReader& r, const YAML::Node& node, ElementContext& ctx) {
  for (const auto& kv : node) {
    KiteSpec k{kv.first.Scalar(), kv.first, kv.second, nullptr};
    if (kv.second["preset"]) k.preset = find_kite_preset(kv.second["preset"].Scalar());
    if (k.spec["point"])
      lower_point_mass(r, k, ctx);
    else
      lower_rigid(r, k, ctx);
  }
}

}  // namespace lagrange::elements
