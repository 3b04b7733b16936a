#include "io/report_visual.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <regex>

namespace lagrange::io {

namespace {

[[noreturn]] void fail(const Model& model, const YAML::Node& at, const std::string& what) {
  const YAML::Mark mark = at.Mark();
  throw ModelError(SourceLoc{model.file, mark.line + 1, mark.column + 1}, what);
}

// A name of the visual section must name a point, a body or an element (a prefix of point
// names up to a '.': `cable` for the tether's `cable.n3`).
void check_name(const Model& model, const YAML::Node& key) {
  if (!key.IsScalar()) fail(model, key, "expected a point, body or element name in visual");
  const std::string name = key.Scalar();
  std::map<std::string, int> probe{{name, 0}};
  auto matches = [&](const std::string& n) { return visual_lookup(probe, n) != nullptr; };
  const bool known = std::any_of(model.points.begin(), model.points.end(),
                                 [&](const Point& p) { return matches(p.name); }) ||
                     std::any_of(model.bodies.begin(), model.bodies.end(),
                                 [&](const Body& b) { return matches(b.name); });
  if (!known)
    fail(model, key,
         fmt::format("expected a point, body or element name in visual, got '{}'", name));
}

std::vector<std::string> name_list(const Model& model, const YAML::Node& n, const char* key) {
  if (!n.IsSequence())
    fail(model, n, fmt::format("expected a list of names for visual.{}, e.g. [bob]", key));
  std::vector<std::string> names;
  for (const auto& item : n) {
    check_name(model, item);
    names.push_back(item.Scalar());
  }
  return names;
}

void expect_map(const Model& model, const YAML::Node& n, const std::string& what) {
  if (!n.IsMap()) fail(model, n, "expected a map name: value for " + what);
}

void read_colors(const Model& model, const YAML::Node& n, Visual& v) {
  expect_map(model, n, "visual.color, e.g. {bob: '#d04040'}");
  static const std::regex css("#[0-9a-fA-F]{3}|#[0-9a-fA-F]{6}|[a-zA-Z]+");
  for (const auto& kv : n) {
    check_name(model, kv.first);
    const std::string c = kv.second.IsScalar() ? kv.second.Scalar() : "";
    if (!std::regex_match(c, css))
      fail(model, kv.second,
           fmt::format("expected a colour ('#rgb', '#rrggbb' or a CSS name such as red) for "
                       "'{}', got '{}'",
                       kv.first.Scalar(), c));
    v.color[kv.first.Scalar()] = c;
  }
}

void read_sizes(const Model& model, const YAML::Node& n, Visual& v) {
  expect_map(model, n, "visual.size, e.g. {bob: 0.1}");
  for (const auto& kv : n) {
    check_name(model, kv.first);
    double s = -1;
    if (kv.second.IsScalar()) {
      try {
        s = kv.second.as<double>();
      } catch (const YAML::Exception&) {
      }
    }
    if (!(s > 0) || !std::isfinite(s))
      fail(model, kv.second,
           fmt::format("expected a positive number (metres) as the size of '{}', got '{}'",
                       kv.first.Scalar(), kv.second.IsScalar() ? kv.second.Scalar() : "a map"));
    v.size[kv.first.Scalar()] = s;
  }
}

}  // namespace

bool visual_listed(const std::vector<std::string>& names, const std::string& name) {
  std::map<std::string, int> probe;
  for (const auto& n : names) probe[n] = 0;
  return visual_lookup(probe, name) != nullptr;
}

Visual read_visual(const Model& model) {
  Visual v;
  std::error_code ec;
  if (model.file.empty() || !std::filesystem::is_regular_file(model.file, ec) ||
      std::filesystem::path(model.file).extension() == ".urdf")
    return v;
  YAML::Node root;
  try {
    root = YAML::LoadFile(model.file);
  } catch (const YAML::Exception&) {
    return v;  // the reader accepted this file; a changed file is not the report's business
  }
  if (!root.IsMap()) return v;
  if (const YAML::Node bodies = root["bodies"]; bodies && bodies.IsMap())
    for (const auto& kv : bodies)
      if (const YAML::Node shape = kv.second["shape"]; shape && shape.IsMap() && shape.size() == 1)
        v.shapes[kv.first.Scalar()] = shape.begin()->first.Scalar();
  const YAML::Node vis = root["visual"];
  if (!vis || vis.IsNull()) return v;
  expect_map(model, vis, "visual (keys color, size, trail, hide)");
  for (const auto& kv : vis) {
    const std::string key = kv.first.Scalar();
    if (key == "color") {
      read_colors(model, kv.second, v);
    } else if (key == "size") {
      read_sizes(model, kv.second, v);
    } else if (key == "trail") {
      v.trail =
          kv.second.IsNull() ? std::vector<std::string>{} : name_list(model, kv.second, "trail");
      v.trail_given = true;
    } else if (key == "hide") {
      v.hide = name_list(model, kv.second, "hide");
    } else {
      fail(model, kv.first,
           fmt::format("unknown key '{}' in visual, expected one of: color, size, trail, hide",
                       key));
    }
  }
  return v;
}

}  // namespace lagrange::io
