#pragma once
// What fuzz_urdf does with one input, shared with its regression test
// (tests/hardening/test_fuzz_regressions.cpp): the bytes written to a `.urdf` file and read as
// `lagrange check robot.urdf` reads it, then derived and compiled when small (model_budget.hpp).

#include <string>

namespace lagrange::fuzz {

/// Writes `bytes` to `path` (a `.urdf` file name), reads it with read_model_file and derives and
/// compiles it when it fits the default Budget. Returns "ok" or the ModelError's message; any
/// other exception escapes.
std::string read_urdf_bytes(const std::string& bytes, const std::string& path);

}  // namespace lagrange::fuzz
