#pragma once
// SHA-256 digests (OpenSSL): machine-code cache records and a study's record of its model.

#include <string>

namespace lagrange {

/// SHA-256 of `bytes` as 64 lowercase hex digits; std::runtime_error if OpenSSL fails.
std::string sha256_hex(const std::string& bytes);

}  // namespace lagrange
