#include <fmt/format.h>

#include "model/model_reader.hpp"

namespace lagrange::model {

void ModelReader::read_energies(const YAML::Node& root) {
  if (root["kinetic"]) m_.kinetic = scalar_expr(root["kinetic"], kAll, "kinetic");
  if (root["potential"]) m_.potential = scalar_expr(root["potential"], kAll, "potential");
}

void ModelReader::read_generalized_forces(const YAML::Node& node) {
  check_keys(node, {}, "generalized_forces");
  for (const auto& kv : node) {
    const std::string& name = kv.first.Scalar();
    int i = m_.coordinate_index(name);
    if (i < 0)
      fail(kv.first,
           fmt::format(
               "expected a coordinate name in generalized_forces, got '{}' (coordinates: {})",
               clip(name), names_of(NameKind::Coordinate)));
    m_.generalized_forces[static_cast<size_t>(i)] =
        scalar_expr(kv.second, kAll, fmt::format("generalized force on '{}'", name));
  }
}

std::vector<NamedExpr> ModelReader::read_named(const YAML::Node& node, const std::string& section) {
  std::vector<NamedExpr> out;
  for (const auto& kv : node) {
    const std::string& name = kv.first.Scalar();
    out.push_back(NamedExpr{name,
                            scalar_expr(kv.second, kAll, fmt::format("{} '{}'", section, name)),
                            src_.at(kv.first)});
  }
  return out;
}

}  // namespace lagrange::model
