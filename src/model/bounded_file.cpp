#include "model/bounded_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "lagrange/error.hpp"

namespace lagrange::model {

std::string read_bounded_file(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw ModelError(SourceLoc{path},
                     fmt::format("cannot open the {}: {}", what, std::strerror(errno)));
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    text.append(chunk, static_cast<size_t>(in.gcount()));
    if (text.size() > kMaxModelBytes)
      throw ModelError(SourceLoc{path}, fmt::format("expected a {} of at most {} MiB, got more",
                                                    what, kMaxModelBytes >> 20));
  }
  if (in.bad()) throw ModelError(SourceLoc{path}, fmt::format("cannot read the {}", what));
  return text;
}

}  // namespace lagrange::model
