#pragma once
// A file's whole text, for tests that read an example, a fixture or an output they wrote.

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace lagrange::test {

/// The whole content of a file, byte for byte ("" when it does not exist).
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace lagrange::test
