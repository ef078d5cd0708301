// SHA-256 of file bytes, for manifests (spec/MANIFEST.md): XXH3 detects corruption, SHA-256 also
// detects tampering (spec/FORMAT.md §8). Computed by OpenSSL's libcrypto, never by hand.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <string>

namespace mosb {

// SHA-256 fed piece by piece, for bytes as they arrive (a download) instead of a second pass.
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(Sha256&&) noexcept;
  Sha256& operator=(Sha256&&) noexcept;
  void update(const void* data, std::size_t size);
  // 64 lowercase hex digits of everything fed so far; the hash then starts again, empty.
  std::string hex();

 private:
  struct Context;
  std::unique_ptr<Context> context_;
};

// 64 lowercase hex digits.
std::string sha256_hex(std::span<const std::byte> bytes);
// Streams the file through the hash in bounded memory; throws mosb::Error (ErrorCode::io) naming
// the file when it cannot be opened or read.
std::string sha256_file(const std::filesystem::path& path);

}  // namespace mosb
