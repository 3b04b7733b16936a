// The `optimal_control:` section (docs/model-language.md, "Optimal control"): controls, horizon,
// objective, bounds, path constraints and boundary values, checked with located errors.

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>

#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

bool name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}

/// Offset of the ')' closing the '(' at `open`, or npos.
size_t closing(const std::string& text, size_t open) {
  int depth = 0;
  for (size_t i = open; i < text.size(); ++i) {
    if (text[i] == '(') ++depth;
    if (text[i] == ')' && --depth == 0) return i;
  }
  return std::string::npos;
}

}  // namespace

StateRef ModelReader::state_ref(const YAML::Node& node, const std::string& what) const {
  const std::string name = scalar(node, what);
  const std::string rate = "_dot";
  const bool velocity =
      name.size() > rate.size() && name.compare(name.size() - rate.size(), rate.size(), rate) == 0;
  const std::string base = velocity ? name.substr(0, name.size() - rate.size()) : name;
  const int index = m_.coordinate_index(base);
  if (index >= 0) return StateRef{static_cast<size_t>(index), velocity, {}, src_.at(node)};
  // A free body's state component (docs/theory.md §4.4): r, R row by row, ṙ and body-frame ω.
  static const std::vector<std::string> positions{"x",   "y",   "z",   "R11", "R12", "R13",
                                                  "R21", "R22", "R23", "R31", "R32", "R33"},
      rates{"vx", "vy", "vz", "wx", "wy", "wz"};
  std::string free_bodies;
  for (const Body& b : m_.bodies) {
    if (!b.free) continue;
    free_bodies += (free_bodies.empty() ? "" : ", ") + b.name;
    const std::string prefix = b.name + ".";
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string part = name.substr(prefix.size());
    const bool rate = std::find(rates.begin(), rates.end(), part) != rates.end();
    if (rate || std::find(positions.begin(), positions.end(), part) != positions.end())
      return StateRef{0, rate, name, src_.at(node)};
    fail(node, fmt::format("expected a state component of the free body '{}' for {} ({}.x, .y, "
                           ".z, .R11 … .R33, .vx, .vy, .vz, .wx, .wy, .wz), got '{}'",
                           b.name, what, b.name, clip(name)));
  }
  fail(node, fmt::format("expected a coordinate or its rate NAME_dot{} for {}, got '{}' "
                         "(coordinates: {}{})",
                         free_bodies.empty() ? "" : ", or a free body's BODY.x … BODY.wz", what,
                         clip(name), names_of(NameKind::Coordinate),
                         free_bodies.empty() ? "" : "; free bodies: " + free_bodies));
}

Bounds ModelReader::read_bounds(const YAML::Node& node, const std::string& what,
                                const std::vector<std::string>& extra_keys) const {
  expect_map(node, fmt::format("{} ({{lower: …, upper: …}})", what));
  std::vector<std::string> keys{"lower", "upper"};
  keys.insert(keys.end(), extra_keys.begin(), extra_keys.end());
  check_keys(node, keys, what);
  Bounds b;
  if (node["lower"])
    b.lower = number(node["lower"], kParams, fmt::format("lower bound of {}", what));
  if (node["upper"])
    b.upper = number(node["upper"], kParams, fmt::format("upper bound of {}", what));
  if (b.lower > b.upper)
    fail(node["lower"], fmt::format("expected the lower bound of {} at most its upper bound {:g}, "
                                    "got {:g}",
                                    what, b.upper, b.lower));
  return b;
}

// J = Σ c_k ∫ L_k dt + Σ c_m mean(M_m) + Φ: each integral(…) and mean(…) is read on its own (the
// rest of the text blanked), then the whole with each renamed to a placeholder symbol of the same
// length, so that every error keeps its column. The placeholders must enter linearly with
// constant factors c.
void ModelReader::read_objective(const YAML::Node& node, OptimalControlSpec& spec) const {
  const std::string what = "the objective";
  if (!node.IsScalar() || node.Scalar().find_first_not_of(" \t\r\n") == std::string::npos)
    fail(node, fmt::format("expected an expression for {}, got {}", what, describe(node)));
  std::string outer = node.Scalar();
  spec.objective_text = outer;
  LocalNames placeholders;
  struct Term {
    GiNaC::symbol placeholder;
    GiNaC::ex expr;
    bool mean;
  };
  std::vector<Term> terms;
  for (const std::string keyword : {"integral", "mean"})
    for (size_t at = outer.find(keyword); at != std::string::npos;
         at = outer.find(keyword, at + 1)) {
      const size_t after = at + keyword.size();
      if ((at > 0 && name_char(outer[at - 1])) || after >= outer.size() || outer[after] != '(')
        continue;
      const size_t close = closing(outer, after);
      if (close == std::string::npos)
        throw ModelError(src_.at(node, after),
                         fmt::format("expected ')' closing {}( (in the objective)", keyword));
      std::string inner(outer.size(), ' ');
      inner.replace(after + 1, close - after - 1, outer, after + 1, close - after - 1);
      if (inner.find_first_not_of(' ') == std::string::npos)
        throw ModelError(src_.at(node, after),
                         fmt::format("expected an expression inside {}()", keyword));
      const GiNaC::ex L =
          parse_text(node, inner, kAll | kColumns, fmt::format("a {} of the objective", keyword))
              .scalar;
      // Never longer than the shortest term it replaces, "mean(x)" (7 characters), for any count
      // the reader's text limit allows.
      const std::string name = fmt::format("_{}{}", keyword[0], terms.size());
      const GiNaC::symbol s(name);
      placeholders[name] = s;
      terms.push_back({s, L, keyword == "mean"});
      outer.replace(at, close + 1 - at, name + std::string(close + 1 - at - name.size(), ' '));
    }
  const Value v = parse_text(node, outer, kAll | kColumns, what, &placeholders);
  if (v.is_vector || v.is_matrix)
    fail(node, fmt::format("expected a scalar for {}, got a vector or matrix", what));
  GiNaC::exmap zero;
  for (const Term& term : terms) zero[term.placeholder] = 0;
  spec.terminal = v.scalar.subs(zero);
  spec.integrand = spec.mean_integrand = 0;
  for (size_t k = 0; k < terms.size(); ++k) {
    const GiNaC::ex factor = v.scalar.diff(terms[k].placeholder);
    if (!evaluate_unrecorded(factor) || factor.has(m_.t) || factor.has(terms[k].placeholder) ||
        !evaluate_unrecorded(factor.subs(zero)))
      fail(node, fmt::format("expected integral and mean terms added with constant factors in {} "
                             "(c*integral(L) + c*mean(M) + terminal terms), got term {} inside "
                             "another function",
                             what, k + 1));
    (terms[k].mean ? spec.mean_integrand : spec.integrand) += factor * terms[k].expr;
  }
}

void ModelReader::read_optimal_control(const YAML::Node& node) {
  expect_map(node, "optimal_control");
  check_keys(node,
             {"controls", "horizon", "minimize", "maximize", "bounds", "path", "initial", "final",
              "periodic", "guess", "intervals", "degree", "stages"},
             "optimal_control");
  OptimalControlSpec spec;
  spec.loc = src_.at(node);
  for (const NamedExpr& c : m_.constraints) spec.multipliers.emplace_back("lambda_" + c.name);
  multipliers_ = spec.multipliers;

  if (!node["controls"]) fail(node, "expected 'controls' in optimal_control (inputs it chooses)");
  expect_map(node["controls"], "controls (a map INPUT: {lower: …, upper: …})");
  for (const auto& kv : node["controls"]) {
    const std::string name = scalar(kv.first, "a control");
    const int index = m_.input_index(name);
    if (index < 0)
      fail(kv.first, fmt::format("expected an input of the model as a control, got '{}' "
                                 "(inputs: {})",
                                 clip(name), names_of(NameKind::Input)));
    ControlSpec c{static_cast<size_t>(index), {}, std::nullopt, false, src_.at(kv.first)};
    if (!kv.second.IsNull()) {
      const std::string what = fmt::format("control '{}'", name);
      c.bounds = read_bounds(kv.second, what, {"guess", "constant", "polynomial"});
      if (kv.second["guess"]) c.guess = number(kv.second["guess"], kParams, "guess of " + what);
      if (kv.second["constant"]) c.constant = boolean(kv.second["constant"], "constant of " + what);
      if (kv.second["polynomial"])
        c.polynomial = boolean(kv.second["polynomial"], "polynomial of " + what);
      if (c.constant && c.polynomial)
        fail(kv.second["polynomial"],
             fmt::format("expected either constant: true or polynomial: true for {}, not both (one "
                         "value over the horizon, or a polynomial on each interval)",
                         what));
    }
    spec.controls.push_back(c);
  }

  if (!node["horizon"]) fail(node, "expected 'horizon' in optimal_control (T, or {lower, upper})");
  const YAML::Node& h = node["horizon"];
  if (h.IsMap()) {
    spec.free_horizon = read_bounds(h, "the horizon", {"guess"});
    const Bounds& b = *spec.free_horizon;
    if (!(b.lower > 0) || !std::isfinite(b.upper))
      fail(h, fmt::format("expected a free horizon with 0 < lower <= upper < inf, got [{:g}, {:g}]",
                          b.lower, b.upper));
    spec.horizon = h["guess"] ? number(h["guess"], kParams, "guess of the horizon")
                              : 0.5 * (b.lower + b.upper);
    if (spec.horizon < b.lower || spec.horizon > b.upper)
      fail(h["guess"], fmt::format("expected the horizon's guess within [{:g}, {:g}], got {:g}",
                                   b.lower, b.upper, spec.horizon));
  } else {
    spec.horizon = number(h, kParams, "the horizon");
    if (!(spec.horizon > 0)) fail(h, fmt::format("expected a horizon > 0, got {:g}", spec.horizon));
  }

  if (node["minimize"] && node["maximize"])
    fail(node["maximize"], "expected one of 'minimize' and 'maximize', got both");
  if (!node["minimize"] && !node["maximize"])
    fail(node, "expected 'minimize' or 'maximize' in optimal_control, got neither");
  spec.maximize = static_cast<bool>(node["maximize"]);
  read_objective(node[spec.maximize ? "maximize" : "minimize"], spec);

  if (const YAML::Node b = node["bounds"]; b && !b.IsNull()) {
    expect_map(b, "bounds (a map NAME: {lower: …, upper: …})");
    for (const auto& kv : b) {
      const StateRef s = state_ref(kv.first, "a bound");
      spec.bounds.push_back({s, read_bounds(kv.second, "bound of '" + kv.first.Scalar() + "'")});
    }
  }

  if (const YAML::Node p = node["path"]; p && !p.IsNull()) {
    expect_map(p, "path (a map NAME: {expression: …, lower: …, upper: …})");
    for (const auto& kv : p) {
      const std::string name = scalar(kv.first, "a path constraint");
      const std::string what = fmt::format("path constraint '{}'", name);
      expect_map(kv.second, what);
      if (!kv.second["expression"])
        fail(kv.first, fmt::format("expected 'expression' in {}, got none", what));
      PathConstraintSpec c{name, scalar_expr(kv.second["expression"], kAll | kColumns, what),
                           read_bounds(kv.second, what, {"expression"}), src_.at(kv.first)};
      if (!std::isfinite(c.bounds.lower) && !std::isfinite(c.bounds.upper))
        fail(kv.first, fmt::format("expected a lower or an upper bound in {}, got neither", what));
      spec.path.push_back(c);
    }
  }

  auto boundary = [&](const char* key) {
    std::vector<BoundaryValue> out;
    const YAML::Node b = node[key];
    if (b.IsNull()) return out;
    expect_map(b, fmt::format("{} (a map NAME: value or {{lower, upper}}, NAME a coordinate or "
                              "NAME_dot)",
                              key));
    for (const auto& kv : b) {
      const std::string what = fmt::format("the {} value of '{}'", key, kv.first.Scalar());
      BoundaryValue v{
          state_ref(kv.first, std::string(key) == "initial" ? "an initial value" : "a final value"),
          {}};
      if (kv.second.IsMap()) {
        v.bounds = read_bounds(kv.second, what);
      } else {
        v.bounds.lower = v.bounds.upper = number(kv.second, kParams, what);
      }
      out.push_back(v);
    }
    return out;
  };
  if (node["initial"]) spec.initial = boundary("initial");
  if (const YAML::Node p = node["periodic"]; p) {
    if (p.IsScalar() && (p.Scalar() == "true" || p.Scalar() == "false")) {
      if (p.Scalar() == "true") {
        for (size_t c = 0; c < m_.coordinates.size(); ++c)
          for (const bool rate : {false, true}) spec.periodic.push_back({c, rate, {}, src_.at(p)});
        // A free body's r, R, ṙ and ω; the transcription keeps the independent ones (RᵀR = 1).
        for (const Body& b : m_.bodies)
          if (b.free)
            for (const char* part : {"x", "y", "z", "R11", "R12", "R13", "R21", "R22", "R23", "R31",
                                     "R32", "R33", "vx", "vy", "vz", "wx", "wy", "wz"})
              spec.periodic.push_back(
                  {0, part[0] == 'v' || part[0] == 'w', b.name + "." + part, src_.at(p)});
      }
    } else {
      expect_seq(p, "periodic (true, or a list of coordinates and rates NAME_dot)");
      for (const auto& item : p) spec.periodic.push_back(state_ref(item, "a periodic component"));
    }
    // A periodic orbit starts where it ends: the initial state is free unless written.
    if (!spec.periodic.empty() && !spec.initial) spec.initial.emplace();
  }
  if (node["final"]) spec.final = boundary("final");
  // A coordinate whose rate is bounded away from zero moves one way only: it cannot return to
  // its start, and Ipopt would only report the problem infeasible.
  for (const StateRef& p : spec.periodic) {
    if (p.velocity || !p.body_state.empty()) continue;
    for (const StateBound& b : spec.bounds) {
      if (b.state.coordinate != p.coordinate || !b.state.velocity || !b.state.body_state.empty())
        continue;
      if (b.bounds.lower > 0 || b.bounds.upper < 0)
        throw ModelError(
            p.loc,
            fmt::format("expected periodic coordinates that can return to their start, got '{}', "
                        "whose rate is bounded to [{:g}, {:g}] (it only {}): leave it out of "
                        "periodic, or let its rate change sign",
                        m_.coordinates[p.coordinate].name, b.bounds.lower, b.bounds.upper,
                        b.bounds.lower > 0 ? "grows" : "shrinks"));
    }
  }

  if (node["guess"] && node["guess"].IsMap()) {
    for (const auto& kv : node["guess"]) {
      const StateRef s = state_ref(kv.first, "a guessed path");
      if (!s.body_state.empty())
        fail(kv.first, fmt::format("expected a coordinate in guess, got the free body's '{}' (a "
                                   "body's motion is guessed by `guess: simulation`, a file, or "
                                   "between its boundary poses)",
                                   clip(kv.first.Scalar())));
      if (s.velocity)
        fail(kv.first, fmt::format("expected a coordinate in guess, got the rate '{}' (a rate "
                                   "follows its coordinate's path: its time derivative)",
                                   clip(kv.first.Scalar())));
      spec.guess_paths.emplace_back(
          s, scalar_expr(kv.second, kParams | kTime,
                         fmt::format("the guessed path of '{}'", kv.first.Scalar())));
    }
  } else if (node["guess"]) {
    spec.guess = scalar(node["guess"], "guess");
    const std::filesystem::path file = spec.guess;
    if (file.extension() == ".csv") {
      std::filesystem::path p = file;
      if (p.is_relative()) p = std::filesystem::path(src_.file()).parent_path() / p;
      std::error_code ec;
      if (!std::filesystem::is_regular_file(p, ec))
        fail(node["guess"], fmt::format("expected a trajectory CSV for guess, cannot open '{}'",
                                        clip(p.string())));
      spec.guess_file = p.string();
      spec.guess.clear();
    } else if (spec.guess != "linear" && spec.guess != "simulation")
      fail(node["guess"], fmt::format("expected guess linear, simulation, a FILE.csv or a map "
                                      "COORDINATE: path(t), got '{}'",
                                      clip(spec.guess)));
  }
  auto count = [&](const char* key, int& out, int lo, int hi) {
    if (!node[key]) return;
    const double n = number(node[key], kParams, key);
    if (n != std::floor(n) || n < lo || n > hi)
      fail(node[key],
           fmt::format("expected {} an integer from {} to {}, got {:g}", key, lo, hi, n));
    out = static_cast<int>(n);
  };
  count("intervals", spec.intervals, 1, 100000);
  count("degree", spec.degree, 1, 5);
  if (node["stages"]) read_stages(node["stages"], spec);
  m_.optimal_control = std::move(spec);
}

}  // namespace lagrange::model
