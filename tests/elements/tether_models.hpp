#pragma once
// Model texts shared by the tether and winch tests.

#include <fmt/format.h>

#include <string>

namespace lagrange::testing {

/// A chain of length L = 10 hung between (0, 0, 0) and (8, 0, 0), gravity −z, viscous damping.
inline std::string hanging_chain(int segments, const std::string& model = "lumped") {
  return fmt::format(R"(parameters: {{span: 8, L: 10, mu: 0.5, g: 9.81, c: 2.0}}
gravity: [0, 0, -g]
tethers:
  chain:
    between: [[0, 0, 0], [span, 0, 0]]
    segments: {}
    model: {}
    length: L
    mass_per_length: mu
    damping: c
)",
                     segments, model);
}

}  // namespace lagrange::testing
