#include "mosb/store_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <string>

#include "mosb/error.hpp"

namespace mosb {

StoreLock::StoreLock(const std::filesystem::path& directory) {
  const auto path = directory / kStoreLockFile;
  const auto fail = [&](const std::string& what) {
    const int saved = errno;
    if (fd_ >= 0) ::close(fd_);
    throw Error(ErrorCode::io, path.string() + ": " + what + ": " + std::strerror(saved));
  };
  fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0666);
  if (fd_ < 0 && errno == ELOOP)
    throw Error(path.string() + ": is a symbolic link, which the store did not make; not followed");
  if (fd_ < 0) fail("cannot open the store's lock");
  struct stat st {};
  if (::fstat(fd_, &st) != 0) fail("cannot open the store's lock");
  if (!S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw Error(path.string() + ": is not a regular file; the store's lock belongs there");
  }
  while (::flock(fd_, LOCK_EX) != 0)
    if (errno != EINTR) fail("cannot lock the store");
}

StoreLock::~StoreLock() {
  ::close(fd_);  // releases the lock
}

}  // namespace mosb
