#include <fmt/format.h>

#include "elements/tether.hpp"
#include "model/model_reader.hpp"

namespace lagrange::elements {

using model::ModelReader;

void declare_winches(ModelReader& r, const YAML::Node& node, ElementContext& ctx) {
  const std::vector<std::string> keys{"tether",  "radius", "inertia",   "total_length",
                                      "initial", "torque", "reeled_out"};
  for (const ElementEntry& entry :
       element_entries(r, node, "winches", "winch", keys, "{tether, radius, inertia, …}")) {
    Winch w;
    w.name = entry.name;
    w.node = entry.spec;
    w.key = entry.key;
    const std::string& what = entry.what;
    const YAML::Node& spec = entry.spec;
    const YAML::Node& key = entry.key;
    if (!spec["tether"])
      r.fail(key, fmt::format("expected 'tether' (the tether it reels) in {}, got none", what));
    w.tether = r.scalar(spec["tether"], "tether of " + what);
    auto positive = [&](const char* field, bool strict) {
      if (!spec[field]) r.fail(key, fmt::format("expected '{}' in {}, got none", field, what));
      GiNaC::ex e =
          r.scalar_expr(spec[field], model::kParams, fmt::format("{} of {}", field, what));
      r.check_sign(e, spec[field], strict, fmt::format("{} of {}", field, what));
      return e;
    };
    w.radius = positive("radius", true);
    w.inertia = positive("inertia", false);
    w.total_length = spec["total_length"] ? positive("total_length", true) : GiNaC::ex(0);
    if (spec["torque"] && spec["reeled_out"])
      r.fail(spec["reeled_out"], fmt::format("expected either 'torque' or a prescribed "
                                             "'reeled_out' in {}, got both",
                                             what));
    if (spec["reeled_out"]) {
      w.reeled_out = r.scalar_expr(spec["reeled_out"], model::kParams | model::kTime,
                                   "reeled-out length of " + what);
      if (spec["initial"])
        r.fail(spec["initial"], fmt::format("expected no 'initial' in {}: its prescribed "
                                            "'reeled_out' sets it",
                                            what));
      const auto l0 = r.initial_value(*w.reeled_out);
      const auto v0 = r.initial_value(w.reeled_out->diff(r.model().t));
      if (!l0 || *l0 <= 0 || !v0)
        r.fail(spec["reeled_out"], fmt::format("expected a positive reeled-out length of {} at "
                                               "t = 0",
                                               what));
      w.initial = *l0;
      w.rate = *v0;
    } else {
      if (!spec["initial"])
        r.fail(key, fmt::format("expected 'initial: {{reeled_out, rate}}' or a prescribed "
                                "'reeled_out' in {}, got neither",
                                what));
      const YAML::Node init = spec["initial"];
      r.expect_map(init, "initial state of " + what + " ({reeled_out, rate})");
      r.check_keys(init, {"reeled_out", "rate", "fixed"}, "initial state of " + what);
      if (init["fixed"]) w.fixed = r.boolean(init["fixed"], "'fixed' of " + what);
      if (!init["reeled_out"])
        r.fail(init, fmt::format("expected 'reeled_out' in the initial state of {}", what));
      w.initial = r.number(init["reeled_out"], model::kParams, "reeled-out length of " + what);
      if (!(w.initial > 0))
        r.fail(init["reeled_out"], fmt::format("expected a positive reeled-out length of {}, got "
                                               "{:g}",
                                               what, w.initial));
      if (init["rate"]) w.rate = r.number(init["rate"], model::kParams, "reel rate of " + what);
    }
    if (spec["total_length"]) {
      const auto total = r.evaluate(w.total_length);
      if (total && *total < w.initial)
        r.fail(spec["total_length"], fmt::format("expected a total tether length of at least the "
                                                 "reeled-out {:g} in {}, got {:g}",
                                                 w.initial, what, *total));
    }
    // A start value given for the coordinate (--initial drum.reeled_out=…) is the winch's.
    const Coordinate& c = r.add_coordinate(w.name + ".reeled_out", w.initial, w.rate, key);
    if (!(c.initial > 0))
      r.fail(key, fmt::format("expected a positive reeled-out length of {}, got {:g} as the start "
                              "value of '{}'",
                              what, c.initial, c.name));
    w.initial = c.initial;
    w.rate = c.rate;
    r.model().coordinates.back().fixed = w.fixed;
    w.coordinate = r.model().coordinates.size() - 1;
    ctx.winches.push_back(w);
  }
}

// docs/theory.md §4.6: the drum (inertia J, radius R) and the tether still on it (μ(L − ℓ),
// moving with the drum's surface at ℓ̇) add T = ½ (J/R² + μ(L − ℓ)) ℓ̇²; the motor torque τ adds
// Q_ℓ = τ/R. A prescribed ℓ(t) is a constraint whose multiplier is the reel force.
void lower_winches(ModelReader& r, ElementContext& ctx) {
  Model& m = r.model();
  for (const Winch& w : ctx.winches) {
    const std::string what = fmt::format("winch '{}'", w.name);
    const Tether* tether = nullptr;
    for (const Tether& t : ctx.tethers)
      if (t.name == w.tether) tether = &t;
    if (tether == nullptr) {
      std::string names;
      for (const Tether& t : ctx.tethers) names += (names.empty() ? "" : ", ") + t.name;
      r.fail(w.node["tether"],
             fmt::format("expected the name of a tether for {}, got '{}' "
                         "(tethers: {})",
                         what, model::clip(w.tether), names.empty() ? "none" : names));
    }
    const Coordinate& c = m.coordinates[w.coordinate];
    const SourceLoc loc = r.source().at(w.key);
    const GiNaC::ex stored = w.total_length.is_zero() ? GiNaC::ex(0) : w.total_length - c.q;
    const GiNaC::ex drum =
        (w.inertia / (w.radius * w.radius) + tether->mass_per_length * stored) / 2 * c.v * c.v;
    m.kinetic += drum;
    ElementSummary summary{fmt::format("Winch '{}' reeling tether '{}'", w.name, w.tether), {}, {}};
    summary.notes.push_back(
        fmt::format("coordinate {} = l (reeled-out length), angle = l/R", c.name));
    summary.equations.emplace_back("T_drum", drum);
    m.outputs.push_back(NamedExpr{w.name + ".speed", c.v, loc});
    m.outputs.push_back(NamedExpr{w.name + ".angle", c.q / w.radius, loc});
    // docs/theory.md §4.11: the drum's momentum balance gives the pull of the line on it,
    // F = (J/R² + μ(L − ℓ)) ℓ̈ − Q_motor, Q_motor = τ/R or the reel's −λ.
    LoadPart load{(w.inertia / (w.radius * w.radius) + tether->mass_per_length * stored) * c.a, {}};
    if (w.torque || w.node["torque"]) {
      const GiNaC::ex tau = r.scalar_expr(w.node["torque"], model::kAll, "torque of " + what);
      m.generalized_forces[w.coordinate] += tau / w.radius;
      summary.equations.emplace_back("Q_" + c.name, tau / w.radius);
      m.outputs.push_back(NamedExpr{w.name + ".power", tau * c.v / w.radius, loc});
      load.expr -= tau / w.radius;
    } else if (w.reeled_out) {
      m.constraints.push_back(NamedExpr{w.name + ".reel", c.q - *w.reeled_out, loc});
      summary.equations.emplace_back("C_reel", m.constraints.back().expr);
      // The reel force on ℓ is −λ; its power −λ ℓ̇.
      m.reactions.push_back(Reaction{w.name + ".power", m.constraints.size() - 1, -c.v, loc});
      load.multipliers.emplace_back(m.constraints.size() - 1, GiNaC::ex(1));
    } else {
      m.outputs.push_back(NamedExpr{w.name + ".power", GiNaC::ex(0), loc});
    }
    m.loads.push_back(Load{w.name + ".load", {load}, loc});
    // ℓ ≤ 0 leaves the drum's domain (a tether of negative length): the run fails there.
    m.fail_when.push_back(
        StopSpec{fmt::format("{} reeled its tether in completely: its reeled-out length must stay "
                             "positive",
                             what),
                 c.name + " < 0", loc});
    m.element_summaries.push_back(std::move(summary));
  }
}

}  // namespace lagrange::elements
