#pragma once
// The `visual:` section of a model file (docs/model-language.md, "How a model looks"): colours,
// sizes, trails and hidden things of the report's 3-D view, by point, body or element name.

#include <map>
#include <string>
#include <vector>

#include "lagrange/model.hpp"

namespace lagrange::io {

struct Visual {
  std::map<std::string, std::string> color;  ///< name → CSS colour
  std::map<std::string, double> size;        ///< name → radius (points) or scale (bodies)
  std::vector<std::string> trail, hide;
  bool trail_given = false;                   ///< `trail:` was written (even empty)
  std::map<std::string, std::string> shapes;  ///< body → declared shape (box, cylinder, sphere)
};

/// Reads `visual:` and the bodies' declared shapes from the model's file; the names must be
/// points, bodies or elements of `model` (ModelError at the name otherwise). Empty when the file
/// cannot be read again (a model read from a string).
Visual read_visual(const Model& model);

/// The value for `name` in a map keyed by visual names: the longest key equal to `name` or a
/// prefix of it up to a '.' (`cable` matches `cable.n3`), or nullptr.
template <class T>
const T* visual_lookup(const std::map<std::string, T>& values, const std::string& name) {
  const T* best = nullptr;
  size_t best_len = 0;
  for (const auto& [key, value] : values)
    if ((name == key || (name.size() > key.size() && name.compare(0, key.size(), key) == 0 &&
                         name[key.size()] == '.')) &&
        key.size() >= best_len) {
      best = &value;
      best_len = key.size();
    }
  return best;
}

/// True when `name` is in `names` in the sense of visual_lookup.
bool visual_listed(const std::vector<std::string>& names, const std::string& name);

}  // namespace lagrange::io
