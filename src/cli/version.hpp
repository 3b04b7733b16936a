#pragma once
// What `lagrange --version` prints: the project version and the git revision of the build.

#include <string>

namespace lagrange::cli {

/// "lagrange 0.1.0 (git 5a215df)": the CMake project version and the configure-time
/// `git describe --always --dirty` of the source tree ("unknown" outside a git checkout).
std::string version_text();

}  // namespace lagrange::cli
