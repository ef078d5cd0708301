// Reading files whole or chunk by chunk, the one read loop of the library: every failure is a
// mosb::Error (ErrorCode::io) "PATH: cannot read: REASON".
#pragma once

#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <span>
#include <string>
#include <type_traits>

#include "mosb/error.hpp"

namespace mosb {

// Calls consume(data, size) for each chunk read from `fd` into `buffer`, from the file's offset to
// its end; `path` names the file in the error. A consume that returns bool stops the read by
// returning false. Returns whether the end was reached (true unless consume stopped it).
template <class Consume>
bool read_chunks(int fd, const std::filesystem::path& path, std::span<char> buffer,
                 Consume&& consume) {
  for (;;) {
    const ssize_t got = ::read(fd, buffer.data(), buffer.size());
    if (got < 0) {
      if (errno == EINTR) continue;
      throw Error(ErrorCode::io, path.string() + ": cannot read: " + std::strerror(errno));
    }
    if (got == 0) return true;
    if constexpr (std::is_same_v<decltype(consume(buffer.data(), std::size_t{})), bool>) {
      if (!consume(buffer.data(), static_cast<std::size_t>(got))) return false;
    } else {
      consume(buffer.data(), static_cast<std::size_t>(got));
    }
  }
}

// The whole text of the file at `path`, read to its end (a size from stat is a hint only: the
// kernel's /proc and /sys files report 0 or 4096).
std::string read_whole_file(const std::filesystem::path& path);

// The whole text of a file a user names (an experiment file, a solver profile): a regular file of
// at most `max_bytes`, opened without waiting (a FIFO would block for ever, a device such as
// /dev/zero never end). Throws mosb::Error (invalid_argument) "PATH: not a regular file" or "PATH:
// more than N bytes", (io) when it cannot be read.
std::string read_regular_file(const std::filesystem::path& path, std::uint64_t max_bytes);

}  // namespace mosb
