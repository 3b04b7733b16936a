#pragma once
// Lookups by `visual:` name (docs/model-language.md, "How a model looks"): the reader keeps the
// section in Model::visual; a name there also stands for an element's points `name.…`.

#include <map>
#include <string>
#include <vector>

namespace lagrange::io {

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
