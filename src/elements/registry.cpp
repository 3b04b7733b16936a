#include "elements/elements.hpp"
#include "elements/kite.hpp"
#include "model/model_reader.hpp"

namespace lagrange::elements {

std::vector<ElementEntry> element_entries(model::ModelReader& r, const YAML::Node& section,
                                          const std::string& section_name, const std::string& kind,
                                          const std::vector<std::string>& keys,
                                          const std::string& shape) {
  r.expect_map(section, section_name + " (a map name: " + shape + ")");
  r.check_keys(section, {}, section_name);
  std::vector<ElementEntry> entries;
  for (const auto& kv : section) {
    ElementEntry e{kv.first, kv.second, kv.first.Scalar(), kind + " '" + kv.first.Scalar() + "'"};
    r.declare_element(e.key);
    r.expect_map(e.spec, e.what + " (a map " + shape + ")");
    r.check_keys(e.spec, keys, e.what);
    entries.push_back(e);
  }
  return entries;
}

const std::vector<std::string>& element_keys() {
  static const std::vector<std::string> keys = {"wind",  "winches", "bridles", "tethers",
                                                "kites", "links",   "urdf"};
  return keys;
}

void declare_elements(model::ModelReader& reader, const YAML::Node& root, ElementContext& ctx) {
  if (auto n = model::section(root, "wind")) read_wind(reader, *n, ctx);
  if (auto n = model::section(root, "winches")) declare_winches(reader, *n, ctx);
  if (auto n = model::section(root, "bridles")) declare_bridles(reader, *n, ctx);
  if (auto n = model::section(root, "tethers")) declare_tethers(reader, *n, ctx);
  if (auto n = model::section(root, "kites")) declare_kites(reader, *n, ctx);
  if (auto n = model::section(root, "links")) declare_links(reader, *n, ctx.links);
  if (auto n = model::section(root, "urdf")) declare_urdf(reader, *n, ctx.urdf);
}

void lower_elements(model::ModelReader& reader, const YAML::Node& root, ElementContext& ctx) {
  if (auto n = model::section(root, "tethers")) lower_tethers(reader, *n, ctx);
  if (auto n = model::section(root, "bridles")) lower_bridles(reader, *n, ctx);
  lower_winches(reader, ctx);
  if (auto n = model::section(root, "kites")) lower_kites(reader, *n, ctx);
  if (model::section(root, "links")) lower_links(reader, ctx.links);
  if (model::section(root, "urdf")) lower_chain(reader, ctx.urdf);
}

}  // namespace lagrange::elements
