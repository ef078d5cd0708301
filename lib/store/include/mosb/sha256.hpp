// SHA-256 of file bytes, for manifests (spec/MANIFEST.md): XXH3 detects corruption, SHA-256 also
// detects tampering (spec/FORMAT.md §8). Computed by OpenSSL's libcrypto, never by hand.
#pragma once

#include <filesystem>
#include <span>
#include <string>

namespace mosb {

// 64 lowercase hex digits.
std::string sha256_hex(std::span<const std::byte> bytes);
// Streams the file through the hash in bounded memory; throws mosb::Error (ErrorCode::io) naming
// the file when it cannot be opened or read.
std::string sha256_file(const std::filesystem::path& path);

}  // namespace mosb
