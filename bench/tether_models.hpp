#pragma once
// The tether and kite models that several benchmarks time (bench_tether, bench_kite,
// bench_linearize): YAML text for any number of segments.

#include <fmt/format.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "support/test_paths.hpp"

namespace lagrange::bench {

/// A tethered balloon on an N-segment lumped tether (simple drag) in a logarithmic wind.
inline std::string balloon_yaml(int segments) {
  return fmt::format(R"(parameters: {{M: 2.0, B: 60, g: 9.81, L: 50, mu: 0.0046, d: 0.002, U: 8,
             z0: 0.1, href: 10, k: 0.6}}
coordinates:
  x: {{initial: 10}}
  y: {{initial: 0}}
  z: {{initial: 48}}
points:
  balloon: [x, y, z]
particles:
  balloon: M
gravity: [0, 0, -g]
wind: {{profile: logarithmic, speed: U, reference_height: href, roughness: z0}}
forces:
  - point: balloon
    force: [0, 0, B]
  - point: balloon
    force: -k*norm(vel(balloon) - [U*log(z/z0)/log(href/z0), 0, 0])*(vel(balloon) - [U*log(z/z0)/log(href/z0), 0, 0])
tethers:
  main:
    between: [[0, 0, 0], balloon]
    segments: {}
    length: L
    mass_per_length: mu
    diameter: d
    drag: simple
)",
                     segments);
}

inline std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("rigid_kite_ap2.yaml lacks " + from);
  return text.replace(at, from.size(), to);
}

/// The rigid AP2 of examples/rigid_kite_ap2.yaml on an N-segment tether in a logarithmic wind
/// (6 m/s at 10 m, z₀ = 0.1 m), or with `logarithmic` false in the example's uniform wind.
inline std::string kite_yaml(int segments, bool logarithmic = true) {
  std::ifstream in(std::string(LAGRANGE_SOURCE_DIR) + "/examples/rigid_kite_ap2.yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = replaced(ss.str(), "segments: 5", fmt::format("segments: {}", segments));
  if (!logarithmic) return text;
  return replaced(text, "wind: {speed: W}",
                  "wind: {profile: logarithmic, speed: W, reference_height: 10, roughness: 0.1}");
}

}  // namespace lagrange::bench
