#include <fmt/format.h>

#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

/// A reference from one point's definition to another point, with where it is written.
struct PointRef {
  size_t target;
  YAML::Node node;
  size_t offset;
};

}  // namespace

// Points may refer to each other in any order: collect the references, order the points
// depth-first without recursion (so long chains cannot overflow the stack), then read them.
void ModelReader::read_points(const YAML::Node& node) {
  std::vector<YAML::Node> defs;
  std::vector<std::vector<PointRef>> refs;
  for (const auto& kv : node) {
    m_.points.push_back(Point{kv.first.Scalar(), {}, src_.at(kv.first)});
    defs.push_back(kv.second);
  }
  point_ready_.assign(defs.size(), false);
  for (const YAML::Node& def : defs) {
    std::vector<YAML::Node> parts;
    if (def.IsSequence()) {
      for (const auto& part : def)
        if (part.IsScalar()) parts.push_back(part);
    } else if (def.IsScalar()) {
      parts.push_back(def);
    }
    refs.emplace_back();
    for (const YAML::Node& part : parts)
      for (const auto& [name, offset] : referenced_names(part.Scalar())) {
        auto it = names_.find(name);
        if (it != names_.end() && it->second.kind == NameKind::Point)
          refs.back().push_back(PointRef{it->second.index, part, offset});
      }
  }

  enum State { kNew, kOnPath, kDone };
  std::vector<State> state(defs.size(), kNew);
  std::vector<size_t> order;
  for (size_t root = 0; root < defs.size(); ++root) {
    if (state[root] != kNew) continue;
    std::vector<std::pair<size_t, size_t>> path{{root, 0}};  // (point, next reference to follow)
    state[root] = kOnPath;
    while (!path.empty()) {
      auto& [i, next] = path.back();
      if (next == refs[i].size()) {
        state[i] = kDone;
        order.push_back(i);
        path.pop_back();
        continue;
      }
      const PointRef& ref = refs[i][next++];
      if (state[ref.target] == kOnPath) {
        std::string cycle;
        bool in = false;
        for (const auto& step : path) {
          in = in || step.first == ref.target;
          if (in) cycle += m_.points[step.first].name + " -> ";
        }
        cycle = clip(cycle + m_.points[ref.target].name, 200);
        throw ModelError(
            src_.at(ref.node, ref.offset),
            fmt::format("expected points that do not depend on themselves, got point '{}' "
                        "defined through itself: {}",
                        m_.points[ref.target].name, cycle));
      }
      if (state[ref.target] == kNew) {
        state[ref.target] = kOnPath;
        path.emplace_back(ref.target, 0);
      }
    }
  }
  for (size_t i : order) {
    m_.points[i].pos = vector_expr(defs[i], kAll, fmt::format("point '{}'", m_.points[i].name));
    point_ready_[i] = true;
  }
}

}  // namespace lagrange::model
