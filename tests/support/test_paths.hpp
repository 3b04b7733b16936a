#pragma once
// Where a test finds the sources and the command. The paths live in one small generated object
// (tests/CMakeLists.txt), not in every test source, so that no test object embeds the clone's
// folder and a compiler cache serves them to a clone anywhere (docs/errors.md, "CI").

#include <string>

namespace lagrange::test {

const char* source_dir();          ///< the source tree: examples/, docs/, fuzz/, tests/
const char* command();             ///< this build's `lagrange` executable
const char* machine_code_cache();  ///< the build tree's machine-code cache for the tests

/// examples/NAME in the source tree.
inline std::string example_path(const std::string& name) {
  return std::string(source_dir()) + "/examples/" + name;
}

}  // namespace lagrange::test

#define LAGRANGE_SOURCE_DIR (::lagrange::test::source_dir())
#define LAGRANGE_BINARY (::lagrange::test::command())
#define LAGRANGE_TEST_CACHE (::lagrange::test::machine_code_cache())
