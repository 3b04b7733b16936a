// `visual:` (docs/model-language.md, "How a model looks") read with the rest of the model into
// Model::visual, from which the report draws: a mistake in it is a model error at its line,
// found by `check` and before any run.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>
#include <string_view>

#include "model/model_reader.hpp"

namespace lagrange::model {

namespace {

// The CSS Color Module 4 named colours.
// clang-format off
constexpr std::string_view kCssNames[] = {
    "aliceblue", "antiquewhite", "aqua", "aquamarine", "azure", "beige", "bisque", "black",
    "blanchedalmond", "blue", "blueviolet", "brown", "burlywood", "cadetblue", "chartreuse",
    "chocolate", "coral", "cornflowerblue", "cornsilk", "crimson", "cyan", "darkblue", "darkcyan",
    "darkgoldenrod", "darkgray", "darkgreen", "darkgrey", "darkkhaki", "darkmagenta",
    "darkolivegreen", "darkorange", "darkorchid", "darkred", "darksalmon", "darkseagreen",
    "darkslateblue", "darkslategray", "darkslategrey", "darkturquoise", "darkviolet", "deeppink",
    "deepskyblue", "dimgray", "dimgrey", "dodgerblue", "firebrick", "floralwhite", "forestgreen",
    "fuchsia", "gainsboro", "ghostwhite", "gold", "goldenrod", "gray", "green", "greenyellow",
    "grey", "honeydew", "hotpink", "indianred", "indigo", "ivory", "khaki", "lavender",
    "lavenderblush", "lawngreen", "lemonchiffon", "lightblue", "lightcoral", "lightcyan",
    "lightgoldenrodyellow", "lightgray", "lightgreen", "lightgrey", "lightpink", "lightsalmon",
    "lightseagreen", "lightskyblue", "lightslategray", "lightslategrey", "lightsteelblue",
    "lightyellow", "lime", "limegreen", "linen", "magenta", "maroon", "mediumaquamarine",
    "mediumblue", "mediumorchid", "mediumpurple", "mediumseagreen", "mediumslateblue",
    "mediumspringgreen", "mediumturquoise", "mediumvioletred", "midnightblue", "mintcream",
    "mistyrose", "moccasin", "navajowhite", "navy", "oldlace", "olive", "olivedrab", "orange",
    "orangered", "orchid", "palegoldenrod", "palegreen", "paleturquoise", "palevioletred",
    "papayawhip", "peachpuff", "peru", "pink", "plum", "powderblue", "purple", "rebeccapurple",
    "red", "rosybrown", "royalblue", "saddlebrown", "salmon", "sandybrown", "seagreen", "seashell",
    "sienna", "silver", "skyblue", "slateblue", "slategray", "slategrey", "snow", "springgreen",
    "steelblue", "tan", "teal", "thistle", "tomato", "turquoise", "violet", "wheat", "white",
    "whitesmoke", "yellow", "yellowgreen"};
// clang-format on

// '#rgb', '#rrggbb' or a CSS colour name (any letter case), checked character by character: no
// regular expression, whose recursion a 50 000-letter name once overflowed (issue 25 item 8).
bool is_colour(const std::string& c) {
  if (!c.empty() && c[0] == '#')
    return (c.size() == 4 || c.size() == 7) &&
           std::all_of(c.begin() + 1, c.end(), [](unsigned char x) { return std::isxdigit(x); });
  if (c.size() > 20) return false;  // longer than the longest name, lightgoldenrodyellow
  std::string lower(c.size(), ' ');
  std::transform(c.begin(), c.end(), lower.begin(),
                 [](unsigned char x) { return static_cast<char>(std::tolower(x)); });
  return std::find(std::begin(kCssNames), std::end(kCssNames), lower) != std::end(kCssNames);
}

}  // namespace

void ModelReader::read_visual(const YAML::Node& node) {
  check_keys(node, {"color", "size", "trail", "hide"}, "visual");
  // A name is a point, a body, or an element whose points are `element.…`.
  auto check_name = [&](const YAML::Node& key) {
    const std::string name = scalar(key, "a point, body or element name in visual");
    auto names = [&](const std::string& n) {
      return n == name || (n.size() > name.size() && n.compare(0, name.size(), name) == 0 &&
                           n[name.size()] == '.');
    };
    if (std::none_of(m_.points.begin(), m_.points.end(),
                     [&](const Point& p) { return names(p.name); }) &&
        std::none_of(m_.bodies.begin(), m_.bodies.end(),
                     [&](const Body& b) { return names(b.name); }))
      fail(key,
           fmt::format("expected a point, body or element name in visual, got '{}'", clip(name)));
    return name;
  };
  if (const YAML::Node colors = node["color"]; colors && !colors.IsNull()) {
    check_keys(colors, {}, "visual.color (e.g. {bob: '#d04040'})");
    for (const auto& kv : colors) {
      const std::string name = check_name(kv.first);
      const std::string c = scalar(kv.second, fmt::format("the colour of '{}'", clip(name)));
      if (!is_colour(c))
        fail(kv.second, fmt::format("expected a colour ('#rgb', '#rrggbb' or a CSS name such as "
                                    "red) for '{}', got '{}'",
                                    clip(name), clip(c)));
      m_.visual.color[name] = c;
    }
  }
  if (const YAML::Node sizes = node["size"]; sizes && !sizes.IsNull()) {
    check_keys(sizes, {}, "visual.size (e.g. {bob: 0.1})");
    for (const auto& kv : sizes) {
      const std::string name = check_name(kv.first);
      double s = -1;
      if (kv.second.IsScalar() && !YAML::convert<double>::decode(kv.second, s)) s = -1;
      if (!(s > 0) || !std::isfinite(s))
        fail(kv.second, fmt::format("expected a positive number (metres) as the size of '{}', "
                                    "got {}",
                                    clip(name), describe(kv.second)));
      m_.visual.size[name] = s;
    }
  }
  for (const char* key : {"trail", "hide"}) {
    const bool trail = std::string(key) == "trail";
    const YAML::Node list = node[key];
    if (trail && list) m_.visual.trail_given = true;
    if (!list || (list.IsNull() && trail)) continue;  // trail: none drawn
    const std::string where = fmt::format("visual.{}", key);
    expect_seq(list, fmt::format("{} (names, e.g. [bob])", where));
    for (const auto& item : list)
      (trail ? m_.visual.trail : m_.visual.hide).push_back(check_name(item));
  }
}

}  // namespace lagrange::model
