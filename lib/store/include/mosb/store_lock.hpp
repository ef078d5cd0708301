// The writers' lock of a store: every command that changes what a store's MANIFEST lists (`store
// add`, later `store pull`) holds it across its read-modify-write of the MANIFEST and the placing
// of the files that MANIFEST will name. Readers (list, verify, instance) take none: the MANIFEST
// is replaced atomically, so they see the old one or the new one.
//
// The lock is flock(LOCK_EX) on DIR/.lock, a file made (mode 0666 & ~umask) on first use and
// never removed: removing it would let a later writer lock a new file while an earlier one still
// holds the old. It is opened with O_NOFOLLOW, so a symlink planted there is refused, not followed.
// The lock is released when the object is destroyed, or by the kernel when the process ends
// (kill -9 included), so a crashed writer never leaves a store locked.
#pragma once

#include <filesystem>
#include <string_view>

namespace mosb {

inline constexpr std::string_view kStoreLockFile = ".lock";

class StoreLock {
 public:
  // Blocks until this process holds the lock of the store in `directory`; throws mosb::Error
  // naming DIR/.lock when it cannot be made or locked (e.g. a read-only store).
  explicit StoreLock(const std::filesystem::path& directory);
  ~StoreLock();
  StoreLock(const StoreLock&) = delete;
  StoreLock& operator=(const StoreLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace mosb
