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

}  // namespace mosb
