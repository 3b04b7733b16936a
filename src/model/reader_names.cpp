#include <fmt/format.h>

#include <algorithm>
#include <cctype>

#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

const char* kind_word(NameKind k) {
  switch (k) {
    case NameKind::Parameter:
      return "parameter";
    case NameKind::Coordinate:
      return "coordinate";
    case NameKind::Input:
      return "input";
    case NameKind::Point:
      return "point";
    case NameKind::Constraint:
      return "constraint";
    case NameKind::Output:
      return "output";
    case NameKind::Derived:
      return "derivative";
    case NameKind::Body:
      return "body";
    case NameKind::BodyPoint:
      return "body point";
    case NameKind::Element:
      return "element";
  }
  return "name";
}

constexpr size_t kMaxNameLength = 100;

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

/// What an expression with these allowed names may contain, for "expected …" messages.
std::string allowed_words(unsigned allowed) {
  if (allowed == kNumbers) return "a number";
  if (allowed == kParams) return "a number or an expression of parameters";
  if (allowed == (kParams | kTime)) return "an expression of t and parameters";
  if (allowed == (kParams | kTime | kInputs)) return "an expression of t, parameters and inputs";
  return "an expression";
}

}  // namespace

void ModelReader::declare(const std::string& name, NameKind kind, size_t index,
                          const YAML::Node& key, const std::string& owner) {
  declare_at(name, kind, index, src_.at(key), owner);
}

void ModelReader::declare_at(const std::string& name, NameKind kind, size_t index,
                             const SourceLoc& loc, const std::string& owner) {
  const char* what = kind_word(kind);
  if (!is_identifier(name))
    throw ModelError(loc, fmt::format("expected a {} name made of letters, digits and '_', got "
                                      "'{}'",
                                      what, clip(name)));
  if (name.size() > kMaxNameLength)
    throw ModelError(loc, fmt::format("expected a {} name of at most {} characters, got '{}'", what,
                                      kMaxNameLength, clip(name)));
  if (name == "t" || name == "pi" || is_builtin_function(name))
    throw ModelError(
        loc, fmt::format("expected a {} name that is not reserved, got '{}' (it is {})", what, name,
                         is_builtin_function(name) ? "a built-in function"
                         : name == "t"             ? "the time"
                                                   : "the constant pi"));
  auto it = names_.find(name);
  if (it != names_.end()) {
    // Report at whichever of the two is written later in the file, naming the other.
    NameEntry mine{kind, index, loc, owner};
    const NameEntry& old = it->second;
    bool old_first =
        std::make_pair(old.loc.line, old.loc.column) <= std::make_pair(loc.line, loc.column);
    const NameEntry& later = old_first ? mine : old;
    const NameEntry& earlier = old_first ? old : mine;
    auto kind_of = [](const NameEntry& e) {
      return e.kind == NameKind::Derived ? fmt::format("derivative of '{}'", e.owner)
                                         : std::string(kind_word(e.kind));
    };
    throw ModelError(
        later.loc, fmt::format("expected a unique name, got {} '{}' which is already the {} at {}",
                               kind_of(later), name, kind_of(earlier), earlier.loc.str()));
  }
  names_.emplace(name, NameEntry{kind, index, loc, owner});
}

void ModelReader::declare_all(const YAML::Node& root) {
  struct Section {
    const char* key;
    NameKind kind;
  };
  const Section sections[] = {{"parameters", NameKind::Parameter},
                              {"coordinates", NameKind::Coordinate},
                              {"inputs", NameKind::Input},
                              {"points", NameKind::Point},
                              {"constraints", NameKind::Constraint},
                              {"outputs", NameKind::Output},
                              {"bodies", NameKind::Body}};
  for (const Section& s : sections) {
    const YAML::Node node = root[s.key];
    if (!node || node.IsNull()) continue;
    check_keys(node, {}, s.key);
    size_t index = 0;
    for (const auto& kv : node) {
      const std::string& name = kv.first.Scalar();
      declare(name, s.kind, index++, kv.first);
      if (s.kind == NameKind::Coordinate || s.kind == NameKind::Input) {
        declare(name + "_dot", NameKind::Derived, 0, kv.first, name);
        declare(name + "_ddot", NameKind::Derived, 0, kv.first, name);
      }
    }
  }
}

std::optional<Value> ModelReader::lookup(const std::string& name, size_t offset,
                                         unsigned allowed) const {
  auto refuse = [&](const std::string& got) -> ExprError {
    return ExprError{offset, fmt::format("expected {}, got {}", allowed_words(allowed), got)};
  };
  if (name == "t") {
    if (!(allowed & kTime)) throw refuse("the time 't'");
    return Value::of(m_.t);
  }
  if (allowed & kColumns)
    if (std::optional<Value> column = column_value(name, offset)) return column;
  auto it = names_.find(name);
  if (it == names_.end()) return body_member(name, offset, allowed);
  const NameEntry& e = it->second;
  std::string got = fmt::format("{} '{}'", kind_word(e.kind), name);
  switch (e.kind) {
    case NameKind::Parameter:
      if (!(allowed & kParams)) throw refuse(got);
      return Value::of(m_.parameters.at(e.index).sym);
    case NameKind::Coordinate:
      if (!(allowed & kCoords)) throw refuse(got);
      return Value::of(m_.coordinates.at(e.index).q);
    case NameKind::Input:
      if (!(allowed & kInputs)) throw refuse(got);
      return Value::of(m_.inputs.at(e.index).u);
    case NameKind::Point:
      if (!(allowed & kPoints)) throw refuse(got);
      if (e.index >= point_ready_.size() || !point_ready_[e.index])
        throw ExprError{offset, fmt::format("expected a point defined before use, got '{}'", name)};
      return Value::of(m_.points.at(e.index).pos);
    case NameKind::BodyPoint:
      if (!(allowed & kPoints)) throw refuse(got);
      return Value::of(body_points_.at(e.index).pos);
    case NameKind::Element:
      throw ExprError{offset, fmt::format("expected one of the element's points or values "
                                          "({0}.<name>), got element '{0}'",
                                          name)};
    case NameKind::Body:
      throw ExprError{offset, fmt::format("expected {0}.r, {0}.R or a point {0}.<name>, got body "
                                          "'{0}'",
                                          name)};
    case NameKind::Derived:
      throw ExprError{
          offset,
          fmt::format("expected a value, got '{}' (write der({}) for the derivative of '{}')", name,
                      e.owner, e.owner)};
    case NameKind::Constraint:
    case NameKind::Output:
      throw ExprError{offset,
                      fmt::format("expected a value, got {} (constraint and output names cannot be "
                                  "used in expressions)",
                                  got)};
  }
  return std::nullopt;
}

// The columns a trajectory records beyond the state, as expressions of (t, q, v, u, p) and the
// multipliers (docs/model-language.md, "Optimal control").
std::optional<Value> ModelReader::column_value(const std::string& name, size_t offset) const {
  for (const Reaction& r : m_.reactions)
    if (r.name == name) return Value::of(multipliers_.at(r.constraint) * r.scale);
  for (size_t c = 0; c < m_.constraints.size(); ++c)
    if (m_.constraints[c].name == name) return Value::of(multipliers_.at(c));
  for (const NamedExpr& o : m_.outputs)
    if (o.name == name) return Value::of(o.expr);
  for (const Load& l : m_.loads)
    if (l.name == name)
      throw ExprError{offset, fmt::format("expected a column of the state, the multipliers and the "
                                          "outputs, got the load '{}' (it needs the "
                                          "accelerations; the tension columns stand in for it)",
                                          name)};
  return std::nullopt;
}

// docs/theory.md §4.4: `body.r` is the origin r (free: its symbols; posed: its position), `body.R`
// the rotation body → world. Points `body.p` are declared names (NameKind::BodyPoint).
std::optional<Value> ModelReader::body_member(const std::string& name, size_t offset,
                                              unsigned allowed) const {
  const size_t dot = name.find('.');
  if (dot == std::string::npos) return std::nullopt;
  const std::string owner = name.substr(0, dot), member = name.substr(dot + 1);
  auto it = names_.find(owner);
  if (it == names_.end() || it->second.kind != NameKind::Body) return std::nullopt;
  const size_t index = it->second.index;
  // The state's columns as the CSV and the bounds name them: plane.x … plane.z, plane.R11 … R33.
  const bool component = member == "x" || member == "y" || member == "z";
  const bool entry = member.size() == 3 && member[0] == 'R' && member[1] >= '1' &&
                     member[1] <= '3' && member[2] >= '1' && member[2] <= '3';
  const bool pose = member == "r" || member == "R" || component || entry;
  if (pose && !(allowed & kCoords))
    throw ExprError{
        offset, fmt::format("expected {}, got '{}' (a body's pose)", allowed_words(allowed), name)};
  if (index >= body_ready_.size() || !body_ready_[index])
    throw ExprError{offset, fmt::format("expected a body defined before use (bodies are read in "
                                        "order), got '{}'",
                                        name)};
  const Body& body = m_.bodies.at(index);
  if (pose) {
    if (member == "r") return Value::of(body.origin());
    if (component) return Value::of(body.origin()[static_cast<size_t>(member[0] - 'x')]);
    if (entry)
      return Value::of(
          body.rot()[static_cast<size_t>(member[1] - '1')][static_cast<size_t>(member[2] - '1')]);
    return Value::of(body.rot());
  }
  std::string points;
  for (const auto& p : body_points_)
    if (p.name.compare(0, dot + 1, owner + ".") == 0)
      points += (points.empty() ? "" : ", ") + p.name.substr(dot + 1);
  throw ExprError{offset, fmt::format("expected r, R, x, y, z, R11 … R33 or a point of body '{}' "
                                      "after '.', got '{}' (points: {})",
                                      owner, clip(member), points.empty() ? "none" : points)};
}

void ModelReader::declare_body_point(const std::string& body, const YAML::Node& key, size_t index) {
  const std::string& name = key.Scalar();
  if (!is_identifier(name) || name.size() > kMaxNameLength)
    fail(key, fmt::format("expected a point name made of letters, digits and '_' (at most {} "
                          "characters) in body '{}', got '{}'",
                          kMaxNameLength, body, clip(name)));
  if (name == "r" || name == "R")
    fail(key, fmt::format("expected a point name other than r and R in body '{}' ({}.r and {}.R "
                          "are its position and rotation), got '{}'",
                          body, body, body, name));
  names_.emplace(body + "." + name, NameEntry{NameKind::BodyPoint, index, src_.at(key), body});
}

std::string ModelReader::names_of(NameKind kind) const {
  std::vector<std::pair<size_t, std::string>> found;
  for (const auto& [name, e] : names_)
    if (e.kind == kind) found.emplace_back(e.index, name);
  if (kind == NameKind::Point)  // body points after the points section's
    for (const auto& [name, e] : names_)
      if (e.kind == NameKind::BodyPoint) found.emplace_back(names_.size() + e.index, name);
  std::sort(found.begin(), found.end());
  std::string out;
  for (size_t i = 0; i < found.size() && i < 10; ++i) out += (i ? ", " : "") + found[i].second;
  if (found.size() > 10) out += fmt::format(", ... ({} in all)", found.size());
  return out.empty() ? "none" : out;
}

}  // namespace lagrange::model
