#include <fmt/format.h>

#include <cmath>

#include "model/latex_names.hpp"
#include "model/model_reader.hpp"
#include "model/size_limits.hpp"

namespace lagrange::model {

void ModelReader::declare_element(const YAML::Node& key) {
  declare(key.Scalar(), NameKind::Element, 0, key);
}

// Generated names contain a dot (`main.node3`), which no user-declared name can: they are
// entered directly, after the element's own name was declared (and checked) by declare().
void ModelReader::add_point(const std::string& name, const Vec3& pos, const YAML::Node& at) {
  add_point(name, pos, src_.at(at));
}

void ModelReader::add_point(const std::string& name, const Vec3& pos, const SourceLoc& loc) {
  m_.points.push_back(Point{name, pos, loc});
  names_.emplace(name, NameEntry{NameKind::Point, m_.points.size() - 1, loc, ""});
  point_ready_.resize(m_.points.size(), false);
  point_ready_.back() = true;
}

const Coordinate& ModelReader::add_coordinate(const std::string& name, double initial, double rate,
                                              const YAML::Node& at) {
  return add_coordinate(name, initial, rate, src_.at(at));
}

const Coordinate& ModelReader::add_coordinate(const std::string& name, double initial, double rate,
                                              const SourceLoc& loc) {
  if (m_.coordinates.size() >= kMaxCoordinates)
    throw ModelError(loc, fmt::format("expected at most {} coordinates in the model (written and "
                                      "generated together), got more at '{}'",
                                      kMaxCoordinates, clip(name)));
  Coordinate c{name,
               GiNaC::symbol(name, latex_name(name)),
               GiNaC::symbol(name + "_dot", latex_name(name, "\\dot")),
               GiNaC::symbol(name + "_ddot", latex_name(name, "\\ddot")),
               start_value(name, initial),
               start_value(name + "_dot", rate),
               false,
               loc};
  m_.coordinates.push_back(c);
  names_.emplace(name, NameEntry{NameKind::Coordinate, m_.coordinates.size() - 1, loc, ""});
  return m_.coordinates.back();
}

const Coordinate& ModelReader::add_named_coordinate(const std::string& name, double initial,
                                                    double rate, const SourceLoc& loc) {
  declare_at(name, NameKind::Coordinate, m_.coordinates.size(), loc);
  declare_at(name + "_dot", NameKind::Derived, 0, loc, name);
  declare_at(name + "_ddot", NameKind::Derived, 0, loc, name);
  return add_coordinate(name, initial, rate, loc);
}

void ModelReader::add_body(const Body& body) {
  declare_at(body.name, NameKind::Body, m_.bodies.size(), body.loc);
  m_.bodies.push_back(body);
  body_ready_.resize(m_.bodies.size(), true);
}

std::optional<double> ModelReader::initial_value(const GiNaC::ex& e) const {
  untraceable(e, "a value at the initial state (a tether's shape, a winch's length, …)");
  GiNaC::exmap values;
  for (const Parameter& p : m_.parameters) values[p.sym] = GiNaC::numeric(p.value);
  values[m_.t] = 0;
  for (const Coordinate& c : m_.coordinates) {
    values[c.q] = GiNaC::numeric(c.initial);
    values[c.v] = GiNaC::numeric(c.rate);
  }
  for (const Body& b : m_.bodies) {
    if (!b.free) continue;
    for (size_t k = 0; k < 3; ++k) {
      values[b.r[k]] = GiNaC::numeric(b.r0[k]);
      values[b.rd[k]] = GiNaC::numeric(b.v0[k]);
      values[b.w[k]] = GiNaC::numeric(b.w0[k]);
    }
    for (size_t k = 0; k < 9; ++k) values[b.R[k]] = GiNaC::numeric(b.R0[k]);
  }
  try {
    for (const Input& u : m_.inputs) {
      values[u.u] = u.expr.subs(values);
      values[u.ud] = u.expr.diff(m_.t).subs(values);
      values[u.udd] = u.expr.diff(m_.t, 2).subs(values);
    }
    const GiNaC::ex r = e.subs(values).evalf();
    if (!GiNaC::is_a<GiNaC::numeric>(r)) return std::nullopt;
    const auto& n = GiNaC::ex_to<GiNaC::numeric>(r);
    if (!n.is_real() || !std::isfinite(n.to_double())) return std::nullopt;
    return n.to_double();
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

std::optional<NameKind> ModelReader::kind_of(const std::string& name) const {
  auto it = names_.find(name);
  if (it == names_.end()) return std::nullopt;
  return it->second.kind;
}

}  // namespace lagrange::model
