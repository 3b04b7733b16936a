// Start values (docs/model-language.md, "initial"): the file's `initial:` section and the
// caller's (`--initial`, Python `initial=`), applied where each coordinate is made, so that what
// is built from the start (a tether's nodes, a winch's length) sees them.

#include <fmt/format.h>

#include "model/model_reader.hpp"

namespace lagrange::model {

void ModelReader::read_start_values(const std::optional<YAML::Node>& section) {
  if (section) {
    expect_map(*section, "initial (coordinate or rate NAME_dot: value)");
    for (const auto& kv : *section) {
      const std::string name = scalar(kv.first, "a name in initial");
      const double value = number(kv.second, kParams, fmt::format("initial value of '{}'", name));
      start_[name] = Start{value, kv.first, true, false};
    }
  }
  std::map<std::string, double> parameters;
  for (const Parameter& p : m_.parameters) parameters[p.name] = p.value;
  for (const auto& [name, text] : given_start_) {
    try {
      start_[name] = Start{evaluate_value_text(text, parameters), YAML::Node(), false, false};
    } catch (const ValueTextError& e) {
      throw ValueTextError(
          fmt::format("expected a finite number after '{}=', got '{}': {}", name, text, e.what()));
    }
  }
}

double ModelReader::start_value(const std::string& name, double otherwise) {
  const auto it = start_.find(name);
  if (it == start_.end()) return otherwise;
  it->second.used = true;
  return it->second.value;
}

void ModelReader::check_start_values_used() const {
  for (const auto& [name, s] : start_)
    if (!s.used && s.in_file)
      fail(s.key, fmt::format("expected a coordinate or a rate NAME_dot in initial, got '{}' "
                              "(coordinates: {})",
                              clip(name), names_of(NameKind::Coordinate)));
}

}  // namespace lagrange::model
