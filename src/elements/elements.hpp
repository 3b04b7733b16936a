#pragma once
// Element kinds (tethers, winches, wind, links): each reads its own top-level section and lowers
// itself into what the core derives — coordinates, points, particles, energies, constraints,
// forces, outputs (docs/model-language.md, "Elements"). The derivation never sees the element
// kinds.

#include <yaml-cpp/yaml.h>

#include <optional>
#include <string>
#include <vector>

#include "elements/links.hpp"
#include "lagrange/model.hpp"

namespace lagrange::model {
class ModelReader;
}

namespace lagrange::elements {

/// The wind field w(x) (docs/theory.md §4.5): a profile of the height above ground along `up`.
struct Wind {
  Vec3 direction{1, 0, 0};  ///< unit vector, horizontal
  Vec3 up{0, 0, 1};         ///< unit vector against gravity
  GiNaC::ex speed = 0;      ///< speed at the reference height (expression of parameters)
  GiNaC::ex scale = 1;      ///< gust factor, an expression of t (and parameters)
  enum class Profile { Uniform, Logarithmic, PowerLaw } profile = Profile::Uniform;
  GiNaC::ex reference_height = 10, roughness = 0.1, exponent = GiNaC::numeric(1, 7);
  /// Wind velocity at a world position (symbolic).
  Vec3 at(const Vec3& position) const;
};

/// A winch drum that sets a tether's length (its coordinate is the reeled-out length).
struct Winch {
  std::string name, tether;
  GiNaC::ex radius, inertia, total_length;
  std::optional<GiNaC::ex> torque;      ///< motor torque, positive in the reel-out sense
  std::optional<GiNaC::ex> reeled_out;  ///< prescribed reeled-out length ℓ(t)
  double initial = 0.0, rate = 0.0;
  bool fixed = false;  ///< `initial: {fixed: true}`: ℓ and ℓ̇ kept by the initial projection
  size_t coordinate = 0;  ///< index of `<winch>.reeled_out` in Model::coordinates
  YAML::Node node, key;
  bool used = false;
};

struct Tether;

/// What element readers share while a file is read.
struct ElementContext {
  ElementContext();
  ~ElementContext();
  std::optional<Wind> wind;
  std::vector<Winch> winches;
  std::vector<Tether> tethers;
  LinkChain links;  ///< `links:`
  LinkChain urdf;   ///< `urdf:`
};

/// One entry `name: {…}` of an element section, already checked.
struct ElementEntry {
  YAML::Node key, spec;
  std::string name;  ///< the element's name, declared
  std::string what;  ///< "<kind> '<name>'", for messages
};

/// The entries of an element section (`tethers: {main: {…}, …}`) in file order: the section is
/// a map, each entry a map with only `keys` (`shape` describes it in messages), each name declared.
std::vector<ElementEntry> element_entries(model::ModelReader& reader, const YAML::Node& section,
                                          const std::string& section_name, const std::string& kind,
                                          const std::vector<std::string>& keys,
                                          const std::string& shape);

/// Top-level keys owned by elements, in the order they are read.
const std::vector<std::string>& element_keys();

/// Phase 1, after points: elements declare their names, coordinates and points.
void declare_elements(model::ModelReader& reader, const YAML::Node& root, ElementContext& ctx);
/// Phase 2, after every user section: elements add particles, energies, constraints, forces,
/// reactions and outputs.
void lower_elements(model::ModelReader& reader, const YAML::Node& root, ElementContext& ctx);

// One reader per kind (wind.cpp, winch.cpp, tether.cpp, bridle.cpp; kites in kite.hpp).
void read_wind(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx);
void declare_winches(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx);
void lower_winches(model::ModelReader& reader, ElementContext& ctx);
void declare_tethers(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx);
void lower_tethers(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx);
// bridle.cpp: lines from points of a kite to a knot, a point with coordinates of its own.
void declare_bridles(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx);
void lower_bridles(model::ModelReader& reader, const YAML::Node& node, ElementContext& ctx);
// links.cpp, link_chain.cpp: joint chains (declared in links.hpp).

}  // namespace lagrange::elements
