#include <fmt/format.h>

#include <algorithm>
#include <set>

#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

}  // namespace

void ModelReader::fail(const YAML::Node& node, const std::string& message) const {
  throw ModelError(src_.at(node), message);
}

std::string ModelReader::describe(const YAML::Node& node) const {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsMap()) return "a map";
  if (node.IsSequence()) return "a list";
  return fmt::format("'{}'", clip(node.Scalar()));
}

void ModelReader::expect_map(const YAML::Node& node, const std::string& what) const {
  if (!node.IsMap()) fail(node, fmt::format("expected a map for {}, got {}", what, describe(node)));
}

void ModelReader::expect_seq(const YAML::Node& node, const std::string& what) const {
  if (!node.IsSequence())
    fail(node, fmt::format("expected a list for {}, got {}", what, describe(node)));
}

std::string ModelReader::scalar(const YAML::Node& node, const std::string& what) const {
  if (!node.IsScalar())
    fail(node, fmt::format("expected a text value for {}, got {}", what, describe(node)));
  return node.Scalar();
}

bool ModelReader::boolean(const YAML::Node& node, const std::string& what) const {
  bool value = false;
  if (!node.IsScalar() || !YAML::convert<bool>::decode(node, value))
    fail(node, fmt::format("expected true or false for {}, got {}", what, describe(node)));
  return value;
}

void ModelReader::check_keys(const YAML::Node& map, const std::vector<std::string>& valid,
                             const std::string& where) const {
  expect_map(map, where);
  std::map<std::string, YAML::Mark> seen;
  for (const auto& kv : map) {
    const YAML::Node& key = kv.first;
    if (!key.IsScalar())
      fail(key, fmt::format("expected a name as key in {}, got {}", where, describe(key)));
    const std::string k = clip(key.Scalar());
    auto [it, fresh] = seen.emplace(k, key.Mark());
    if (!fresh)
      fail(key, fmt::format("expected each key once in {}, got '{}' again (first at {})", where, k,
                            src_.at(it->second).str()));
    if (!valid.empty() && std::find(valid.begin(), valid.end(), k) == valid.end())
      fail(key, fmt::format("unknown key '{}' in {}, expected one of: {}", k, where, join(valid)));
  }
}

}  // namespace lagrange::model
