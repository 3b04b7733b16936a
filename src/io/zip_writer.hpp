#pragma once
// A zip archive of stored (uncompressed) entries, as an FMU may be (FMI 2.0 §2.3 allows the
// methods "store" and "deflate"): no zip program or library at export time, and the same bytes for
// the same files (every entry dated 1980-01-01).

#include <string>
#include <utility>
#include <vector>

namespace lagrange {

/// The bytes of a zip archive holding `entries` (path inside the archive, content), in order.
/// Throws std::invalid_argument for an archive past the 4 GiB of the format without Zip64.
std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& entries);

/// The CRC-32 of `data` (ISO 3309, the one zip uses).
unsigned long crc32_of(const std::string& data);

}  // namespace lagrange
