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

// A vector-valued entry `name: v` stands for three scalars name.x, name.y, name.z (a fixed
// pivot `pivot: body.r + body.R*[0, 0, -d]` is three constraints with three multipliers).
std::vector<NamedExpr> ModelReader::read_named(const YAML::Node& node, const std::string& section) {
  std::vector<NamedExpr> out;
  // A vector's components `name.x`, `name.y`, `name.z`. A constraint's component that is
  // identically zero (a planar loop closure's z) constrains nothing and would make the
  // constraints' Jacobian rank-deficient: it is dropped, with a note.
  const auto components = [&](const std::string& name, const Vec3& v, const YAML::Node& key) {
    std::string dropped;
    size_t kept = 0;
    for (size_t k = 0; k < 3; ++k) {
      const std::string component = name + "." + std::string(1, char('x' + k));
      if (section == "constraint" && (v[k].is_zero() || v[k].expand().is_zero())) {
        dropped += (dropped.empty() ? "'" : ", '") + component + "'";
        continue;
      }
      out.push_back(NamedExpr{component, v[k], src_.at(key)});
      ++kept;
    }
    if (kept == 0)
      fail(key, fmt::format("expected a constraint that constrains something, got '{}', "
                            "identically zero in every component",
                            name));
    if (!dropped.empty())
      fmt::print(stderr,
                 "{}: note: {} of constraint '{}' {} identically zero (a planar constraint): "
                 "dropped\n",
                 src_.at(key).str(), dropped, name, kept == 2 ? "is" : "are");
  };
  for (const auto& kv : node) {
    const std::string& name = kv.first.Scalar();
    const std::string what = fmt::format("{} '{}'", section, name);
    const SourceLoc loc = src_.at(kv.first);
    if (kv.second.IsSequence()) {
      components(name, vector_expr(kv.second, kAll, what), kv.first);
      continue;
    }
    const Value v = parse(kv.second, kAll, what);
    if (v.is_matrix)
      fail(kv.second, fmt::format("expected a scalar or a vector for {}, got a "
                                  "matrix",
                                  what));
    if (!v.is_vector) {
      out.push_back(NamedExpr{name, v.scalar, loc});
      continue;
    }
    components(name, v.vec, kv.first);
  }
  return out;
}

}  // namespace lagrange::model
