#include "mosb/internal/read_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>

#include <array>

namespace mosb {

std::string read_whole_file(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw Error(ErrorCode::io, path.string() + ": cannot read: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  std::string text;
  struct stat st {};
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0)
    text.reserve(static_cast<std::size_t>(st.st_size));
  std::array<char, std::size_t{64} * 1024> buffer;
  read_chunks(fd, path, buffer,
              [&](const char* data, std::size_t size) { text.append(data, size); });
  return text;
}

std::string read_regular_file(const std::filesystem::path& path, std::uint64_t max_bytes) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw Error(ErrorCode::io, path.string() + ": cannot read: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw Error(ErrorCode::invalid_argument, path.string() + ": not a regular file");
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes)
    throw Error(ErrorCode::invalid_argument,
                path.string() + ": more than " + std::to_string(max_bytes) + " bytes");
  std::string text;
  text.reserve(static_cast<std::size_t>(st.st_size));
  std::array<char, std::size_t{64} * 1024> buffer;
  read_chunks(fd, path, buffer, [&](const char* data, std::size_t size) {
    if (size > max_bytes - text.size())  // grown since fstat
      throw Error(ErrorCode::invalid_argument,
                  path.string() + ": more than " + std::to_string(max_bytes) + " bytes");
    text.append(data, size);
  });
  return text;
}

}  // namespace mosb
