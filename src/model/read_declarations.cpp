#include <fmt/format.h>

#include <iterator>

#include "model/latex_names.hpp"
#include "model/model_reader.hpp"
#include "model/size_limits.hpp"

namespace lagrange::model {

void ModelReader::read_parameters(const YAML::Node& node) {
  for (const auto& kv : node) {
    const std::string& name = kv.first.Scalar();
    Parameter p{name, GiNaC::symbol(name, latex_name(name)), 0.0, src_.at(kv.first)};
    p.value = number(kv.second, kNumbers, fmt::format("parameter '{}'", name));
    if (auto it = overrides_.find(name); it != overrides_.end()) p.value = it->second;
    m_.parameters.push_back(p);
  }
}

void ModelReader::check_overrides() const {
  for (const auto& [name, value] : overrides_)
    if (m_.parameter_index(name) < 0)
      throw ParameterOverrideError(fmt::format("unknown parameter '{}' (parameters: {})", name,
                                               names_of(NameKind::Parameter)));
}

void ModelReader::read_coordinates(const YAML::Node& node) {
  // `coordinates: {}` says what an absent key says (a model of free bodies or tethers).
  if (node.IsMap() && node.size() == 0) return;
  if (node.size() == 0) fail(node, "expected at least one coordinate in coordinates, got none");
  if (node.size() > kMaxCoordinates) {
    auto it = node.begin();
    std::advance(it, kMaxCoordinates);
    fail(it->first,
         fmt::format("expected at most {} coordinates, got {}", kMaxCoordinates, node.size()));
  }
  for (const auto& kv : node) {
    const std::string& name = kv.first.Scalar();
    std::string what = fmt::format("coordinate '{}'", name);
    const YAML::Node& spec = kv.second;
    if (!spec.IsMap())
      fail(spec.IsNull() ? kv.first : spec,
           fmt::format("expected a map {{initial: …, rate: …}} for {}, got {}", what,
                       describe(spec)));
    check_keys(spec, {"initial", "rate", "fixed"}, what);
    Coordinate c{name,
                 GiNaC::symbol(name, latex_name(name)),
                 GiNaC::symbol(name + "_dot", latex_name(name, "\\dot")),
                 GiNaC::symbol(name + "_ddot", latex_name(name, "\\ddot")),
                 0.0,
                 0.0,
                 false,
                 src_.at(kv.first)};
    if (!spec["initial"]) fail(kv.first, fmt::format("expected 'initial' in {}, got none", what));
    // A start value given (`initial:` section, --initial) replaces the one written here, which
    // is still read for its mistakes but not traced (a study would replay it).
    const std::string initial_what = fmt::format("initial value of {}", what);
    if (start_.count(name) != 0) {
      (void)scalar_expr(spec["initial"], kParams, initial_what);
      c.initial = start_value(name, 0.0);
    } else {
      c.initial = coordinate_number(spec["initial"], initial_what, c, false);
    }
    if (start_.count(name + "_dot") != 0) {
      if (spec["rate"]) (void)scalar_expr(spec["rate"], kParams, fmt::format("rate of {}", what));
      c.rate = start_value(name + "_dot", 0.0);
    } else if (spec["rate"]) {
      c.rate = coordinate_number(spec["rate"], fmt::format("rate of {}", what), c, true);
    }
    if (spec["fixed"]) c.fixed = boolean(spec["fixed"], fmt::format("'fixed' of {}", what));
    m_.coordinates.push_back(c);
  }
}

void ModelReader::read_inputs(const YAML::Node& node) {
  // Symbols first, so that each input's expression is read with every input declared.
  for (const auto& kv : node) {
    const std::string& name = kv.first.Scalar();
    m_.inputs.push_back(Input{name, GiNaC::symbol(name, latex_name(name)),
                              GiNaC::symbol(name + "_dot", latex_name(name, "\\dot")),
                              GiNaC::symbol(name + "_ddot", latex_name(name, "\\ddot")), 0,
                              src_.at(kv.first)});
  }
  // `name: expression`, or `name: {value: expression, external: true}` for an input that a
  // caller sets between steps (the expression is its value when none does).
  size_t i = 0;
  for (const auto& kv : node) {
    Input& u = m_.inputs[i++];
    const std::string what = fmt::format("input '{}'", u.name);
    const YAML::Node& spec = kv.second;
    if (!spec.IsMap()) {
      u.expr = scalar_expr(spec, kParams | kTime, what);
      continue;
    }
    check_keys(spec, {"value", "external"}, what);
    if (!spec["value"]) fail(kv.first, fmt::format("expected 'value' in {}, got none", what));
    u.expr = scalar_expr(spec["value"], kParams | kTime, fmt::format("value of {}", what));
    if (spec["external"])
      u.external = boolean(spec["external"], fmt::format("'external' of {}", what));
  }
}

}  // namespace lagrange::model
