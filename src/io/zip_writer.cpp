// Zip archives of stored entries (PKWARE APPNOTE.TXT 6.3.10, sections 4.3.7, 4.3.12, 4.3.16).

#include "io/zip_writer.hpp"

#include <array>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace lagrange {

namespace {

void put16(std::string& s, uint32_t v) {
  s += static_cast<char>(v & 0xff);
  s += static_cast<char>((v >> 8) & 0xff);
}

void put32(std::string& s, uint32_t v) {
  put16(s, v & 0xffff);
  put16(s, v >> 16);
}

constexpr uint32_t kDosDate = (0 << 9) | (1 << 5) | 1;  // 1980-01-01, time 00:00:00

}  // namespace

unsigned long crc32_of(const std::string& data) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  uint32_t c = 0xffffffffu;
  for (unsigned char b : data) c = table[(c ^ b) & 0xff] ^ (c >> 8);
  return c ^ 0xffffffffu;
}

std::string zip_stored(const std::vector<std::pair<std::string, std::string>>& entries) {
  std::string archive, directory;
  for (const auto& [name, content] : entries) {
    const uint64_t offset = archive.size();
    if (content.size() >= std::numeric_limits<uint32_t>::max() ||
        offset + content.size() + 30 + name.size() >= std::numeric_limits<uint32_t>::max())
      throw std::invalid_argument("zip: archive larger than 4 GiB (no Zip64 support): " + name);
    const uint32_t crc = static_cast<uint32_t>(crc32_of(content));
    const uint32_t size = static_cast<uint32_t>(content.size());
    // Fields shared by the local header and the central directory: version needed 2.0, flags 0,
    // method 0 (stored), time, date, CRC, sizes, name length.
    std::string common;
    put16(common, 20);
    put16(common, 0);
    put16(common, 0);
    put16(common, 0);
    put16(common, kDosDate);
    put32(common, crc);
    put32(common, size);
    put32(common, size);
    put16(common, static_cast<uint32_t>(name.size()));
    put32(archive, 0x04034b50);  // local file header
    archive += common;
    put16(archive, 0);  // extra field length
    archive += name + content;
    put32(directory, 0x02014b50);     // central directory header
    put16(directory, (3 << 8) | 20);  // made by Unix, version 2.0
    directory += common;
    put16(directory, 0);                                     // extra field length
    put16(directory, 0);                                     // comment length
    put16(directory, 0);                                     // disk number
    put16(directory, 0);                                     // internal attributes
    put32(directory, static_cast<uint32_t>(0100644) << 16);  // external: -rw-r--r--
    put32(directory, static_cast<uint32_t>(offset));
    directory += name;
  }
  const uint64_t at = archive.size();
  if (at + directory.size() >= std::numeric_limits<uint32_t>::max())
    throw std::invalid_argument("zip: archive larger than 4 GiB (no Zip64 support)");
  archive += directory;
  put32(archive, 0x06054b50);  // end of central directory
  put16(archive, 0);
  put16(archive, 0);
  put16(archive, static_cast<uint32_t>(entries.size()));
  put16(archive, static_cast<uint32_t>(entries.size()));
  put32(archive, static_cast<uint32_t>(directory.size()));
  put32(archive, static_cast<uint32_t>(at));
  put16(archive, 0);
  return archive;
}

}  // namespace lagrange
