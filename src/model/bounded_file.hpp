#pragma once
// Files the reader takes in whole (a model file, a URDF file), read up to a bound so that
// /dev/zero, a FIFO that never ends or a runaway file cannot fill memory (issue 25 item 6,
// issue 37 item 13).

#include <cstddef>
#include <string>

namespace lagrange::model {

/// The largest model or URDF file read (a model of 2000 coordinates is a few hundred KiB).
constexpr size_t kMaxModelBytes = size_t{16} << 20;

/// The bytes of `path`, a `what` ("model file", "URDF file"): ModelError at `path` when it cannot
/// be opened or read, or holds more than kMaxModelBytes (found at that many, not at its end).
std::string read_bounded_file(const std::string& path, const std::string& what);

}  // namespace lagrange::model
