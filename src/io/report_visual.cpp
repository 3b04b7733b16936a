#include "io/report_visual.hpp"

namespace lagrange::io {

bool visual_listed(const std::vector<std::string>& names, const std::string& name) {
  std::map<std::string, int> probe;
  for (const auto& n : names) probe[n] = 0;
  return visual_lookup(probe, name) != nullptr;
}

}  // namespace lagrange::io
