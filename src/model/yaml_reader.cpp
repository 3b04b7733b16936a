#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <optional>

#include "elements/elements.hpp"
#include "lagrange/reader.hpp"
#include "model/bounded_file.hpp"
#include "model/model_reader.hpp"

namespace lagrange {

namespace model {

namespace {

const std::vector<std::string>& top_level_keys() {
  // clang-format off
  static const std::vector<std::string> keys = {
      "name",        "parameters", "coordinates", "inputs",    "bodies",
      "points",      "particles",  "gravity",     "kinetic",   "potential",
      "generalized_forces",        "forces",      "torques",   "springs",
      "dampers",     "constraints", "outputs",    "stabilization", "simulate",
      "stop_when",   "metrics",    "visual",    "optimal_control", "initial"};  // visual: read into Model::visual, drawn by the report
  // clang-format on
  static const std::vector<std::string> all = [] {
    std::vector<std::string> k = keys;
    const auto& e = elements::element_keys();
    k.insert(k.end(), e.begin(), e.end());
    return k;
  }();
  return all;
}

}  // namespace

ModelReader::ModelReader(const SourceText& src, const ParameterOverrides& overrides,
                         ReadTrace* trace, const StartValues& start)
    : src_(src), overrides_(overrides), trace_(trace), given_start_(start) {}

Model ModelReader::read(const YAML::Node& root) {
  if (!root.IsMap())
    throw ModelError(src_.at(root.IsNull() ? YAML::Mark() : root.Mark()),
                     fmt::format("expected a map of model keys (name, coordinates, …), got {}",
                                 root.IsNull() ? "an empty document" : describe(root)));
  check_keys(root, top_level_keys(), "the model");
  m_.file = src_.file();
  m_.name = std::filesystem::path(src_.file()).stem().string();
  if (root["name"]) m_.name = scalar(root["name"], "name");
  declare_all(root);

  if (auto n = section(root, "parameters")) read_parameters(*n);
  check_overrides();
  watch_parameters();
  read_start_values(section(root, "initial"));
  if (auto n = section(root, "coordinates")) read_coordinates(*n);
  if (auto n = section(root, "inputs")) read_inputs(*n);
  if (auto n = section(root, "bodies")) read_bodies(*n);
  if (auto n = section(root, "points")) read_points(*n);
  m_.points.insert(m_.points.end(), body_points_.begin(), body_points_.end());
  if (auto n = section(root, "gravity")) {
    m_.gravity = vector_expr(*n, kParams | kTime | kInputs, "gravity");
    const Vec3& g = *m_.gravity;
    warn_implausible(GiNaC::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]), *n, Quantity::Gravity,
                     "the magnitude of gravity");
  }
  elements::ElementContext elements;
  elements::declare_elements(*this, root, elements);
  const bool has_free_body =
      std::any_of(m_.bodies.begin(), m_.bodies.end(), [](const Body& b) { return b.free; });
  if (m_.coordinates.empty() && !has_free_body)
    throw ModelError(src_.at(root),
                     "expected a 'coordinates' key with at least one coordinate (or a body with "
                     "'frame: free', or a tether), got none");
  m_.generalized_forces.assign(m_.coordinates.size(), GiNaC::ex(0));
  read_energies(root);
  if (auto n = section(root, "generalized_forces")) read_generalized_forces(*n);
  if (auto n = section(root, "particles")) read_particles(*n);
  if (auto n = section(root, "forces")) read_forces(*n);
  if (auto n = section(root, "torques")) read_torques(*n);
  if (auto n = section(root, "springs")) read_springs(*n);
  if (auto n = section(root, "dampers")) read_dampers(*n);
  if (auto n = section(root, "constraints")) m_.constraints = read_named(*n, "constraint");
  if (auto n = section(root, "outputs")) m_.outputs = read_named(*n, "output");
  elements::lower_elements(*this, root, elements);
  if (auto n = section(root, "stabilization")) read_stabilization(*n);
  if (auto n = section(root, "simulate")) read_simulate(*n);
  if (auto n = section(root, "stop_when")) read_stop_when(*n);
  if (auto n = section(root, "metrics")) read_metrics(*n);
  if (auto n = section(root, "visual")) read_visual(*n);
  if (auto n = section(root, "optimal_control")) read_optimal_control(*n);
  check_start_values_used();
  warn_angle_parameters();
  return m_;
}

}  // namespace model

Model read_model_string(const std::string& yaml_text, const std::string& file_label,
                        const ParameterOverrides& overrides, ReadTrace* trace,
                        const StartValues& start) {
  if (yaml_text.size() > model::kMaxModelBytes)  // a file is cut off at read; text given whole
    throw ModelError(SourceLoc{file_label},
                     fmt::format("expected a model of at most {} MiB, got {}",
                                 model::kMaxModelBytes >> 20, yaml_text.size()));
  std::string text = yaml_text.rfind("\xEF\xBB\xBF", 0) == 0 ? yaml_text.substr(3) : yaml_text;
  model::SourceText src(std::move(text), file_label);
  model::check_yaml_text(src);
  YAML::Node root;
  try {
    model::check_single_document(src);
    root = YAML::Load(src.text());
  } catch (const YAML::Exception& e) {
    const SourceLoc at = src.at(e.mark);
    if (const auto tab = model::indentation_tab(src); tab && (at.line == 0 || tab->line <= at.line))
      throw ModelError(*tab,
                       "YAML forbids tabs for indentation, got a tab here (indent with "
                       "spaces)");
    throw ModelError(at, fmt::format("expected valid YAML, got a syntax error: {}", e.msg));
  }
  try {
    return model::ModelReader(src, overrides, trace, start).read(root);
  } catch (const YAML::Exception& e) {
    throw ModelError(src.at(e.mark), fmt::format("expected a well-formed model, got: {}", e.msg));
  }
}

namespace {

Model read_file(const std::string& path, const ParameterOverrides& overrides, ReadTrace* trace,
                const StartValues& start = {}) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw ModelError(SourceLoc{path}, "expected a model file, got a directory");
  if (std::filesystem::path(path).extension() == ".urdf") {
    // A URDF robot on its own: zero torques, gravity −9.81 along z, named after <robot name>
    // (docs/model-language.md).
    // Relative to the file itself, so that messages name the path as typed.
    // Both go into single-quoted YAML scalars, where a quote is written twice.
    auto quoted = [](const std::string& text) {
      std::string out;
      for (char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
      return out;
    };
    const std::filesystem::path file(path);
    return read_model_string(
        fmt::format("name: '{}'\nurdf: '{}'\ngravity: [0, 0, -9.81]\n",
                    quoted(file.stem().string()), quoted(file.filename().string())),
        path, overrides, trace, start);
  }
  return read_model_string(model::read_bounded_file(path, "model file"), path, overrides, trace,
                           start);
}

}  // namespace

Model read_model_file(const std::string& path, const ParameterOverrides& overrides) {
  return read_file(path, overrides, nullptr);
}

Model read_model_file(const std::string& path, const ParameterOverrides& overrides,
                      ReadTrace& trace) {
  return read_file(path, overrides, &trace);
}

Model read_model_file(const std::string& path, const ParameterOverrides& overrides,
                      const StartValues& start) {
  return read_file(path, overrides, nullptr, start);
}

}  // namespace lagrange
