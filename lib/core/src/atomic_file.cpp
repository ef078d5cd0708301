#include "mosb/atomic_file.hpp"

#include <fcntl.h>
#include <sys/random.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>

#include "mosb/error.hpp"

namespace mosb {

namespace {

// --- The registry of live temporaries, read by the signal handler --------------------------------
// Fixed storage and lock-free atomics only, so the handler stays async-signal-safe. A slot is
// claimed (free -> filling), filled, then published (live); the handler unlinks live slots only.

constexpr int kSlots = 64;  // more concurrent writers than this are written but not registered
enum SlotState : int { kFree = 0, kFilling = 1, kLive = 2 };
struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};
Slot g_slots[kSlots];
static_assert(std::atomic<int>::is_always_lock_free);

int register_temporary(const std::string& path) {
  if (path.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
    g_slots[i].state.store(kLive, std::memory_order_release);
    return i;
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0) g_slots[slot].state.store(kFree, std::memory_order_release);
}

extern "C" void remove_temporaries_and_reraise(int signal_number) {
  const int saved_errno = errno;
  for (auto& slot : g_slots)
    if (slot.state.load(std::memory_order_acquire) == kLive) ::unlink(slot.path);
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  ::sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  sigset_t just_this;
  ::sigemptyset(&just_this);
  ::sigaddset(&just_this, signal_number);
  ::sigprocmask(SIG_UNBLOCK, &just_this, nullptr);
  ::raise(signal_number);  // delivered now, with the default action: the process ends
  errno = saved_errno;
}

// The signals that end a process by default and that a user or a session sends on purpose: Ctrl-C,
// kill, a closed terminal (SIGHUP, e.g. an ssh session that drops) and Ctrl-\.
constexpr int kCleanupSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

// Blocks the cleanup signals while a temporary is created and registered, so no signal can come
// between the two (the file would be left) or between an unlink and the slot's release.
class SignalsBlocked {
 public:
  SignalsBlocked() {
    sigset_t set;
    ::sigemptyset(&set);
    for (int signal_number : kCleanupSignals) ::sigaddset(&set, signal_number);
    ::pthread_sigmask(SIG_BLOCK, &set, &saved_);
  }
  ~SignalsBlocked() { ::pthread_sigmask(SIG_SETMASK, &saved_, nullptr); }
  SignalsBlocked(const SignalsBlocked&) = delete;
  SignalsBlocked& operator=(const SignalsBlocked&) = delete;

 private:
  sigset_t saved_;
};

// --- Temporary names
// ------------------------------------------------------------------------------
// `.NAME.tmp-PID-XXXXXX`; NAME is cut so the whole name fits NAME_MAX (255) bytes.

std::string temporary_prefix(const std::string& file_name) {
  return "." + file_name.substr(0, 200) + ".tmp-";
}

constexpr char kSuffixAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
constexpr std::size_t kSuffixLength = 6;

std::string random_suffix() {
  std::array<unsigned char, kSuffixLength> bytes{};
  if (::getrandom(bytes.data(), bytes.size(), 0) != static_cast<ssize_t>(bytes.size())) {
    // O_EXCL keeps a guessable name safe; the retry loop keeps it unique.
    static std::atomic<unsigned> counter{0};
    unsigned value = counter++ * 2654435761u ^ static_cast<unsigned>(::getpid());
    for (auto& b : bytes) b = static_cast<unsigned char>(value >>= 5);
  }
  std::string suffix;
  for (auto b : bytes) suffix += kSuffixAlphabet[b % (sizeof kSuffixAlphabet - 1)];
  return suffix;
}

// The PID in `name` when it is `prefix` + PID + '-' + a suffix of the right length.
std::optional<pid_t> temporary_pid(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return {};
  const std::string rest = name.substr(prefix.size());
  const auto dash = rest.find('-');
  if (dash == 0 || dash == std::string::npos || dash > 10 ||
      rest.size() - dash - 1 != kSuffixLength)
    return {};
  long long pid = 0;
  for (std::size_t i = 0; i < dash; ++i) {
    if (rest[i] < '0' || rest[i] > '9') return {};
    pid = pid * 10 + (rest[i] - '0');
  }
  for (std::size_t i = dash + 1; i < rest.size(); ++i)
    if (!std::strchr(kSuffixAlphabet, rest[i])) return {};
  if (pid <= 0 || pid > INT_MAX) return {};
  return static_cast<pid_t>(pid);
}

std::mutex g_handler_mutex;
std::function<void(const std::filesystem::path&)> g_stale_handler;

// Removes this target's temporaries left by processes that no longer exist.
void remove_stale_temporaries(const std::filesystem::path& directory, const std::string& prefix) {
  std::error_code ec;
  std::filesystem::directory_iterator it(directory, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const auto pid = temporary_pid(name, prefix);
    if (!pid || *pid == ::getpid()) continue;
    if (!process_has_ended(*pid)) continue;
    struct stat st {};
    if (::lstat(it->path().c_str(), &st) != 0 || !S_ISREG(st.st_mode)) continue;
    if (::unlink(it->path().c_str()) != 0) continue;
    std::lock_guard lock(g_handler_mutex);
    if (g_stale_handler) g_stale_handler(it->path());
  }
}

std::string errno_text() {
  return std::strerror(errno);
}

}  // namespace

AtomicFile::AtomicFile(std::filesystem::path target, Existing existing)
    : target_(std::move(target)) {
  const std::string shown = target_.string();
  struct stat existing_stat {};
  if (existing == Existing::rewrite_in_place) {
    std::error_code ec;
    auto resolved = std::filesystem::canonical(target_, ec);  // the file a symlink leads to
    if (ec) throw Error(shown + ": cannot rewrite in place: " + ec.message());
    if (::stat(resolved.c_str(), &existing_stat) != 0)
      throw Error(shown + ": cannot rewrite in place: " + errno_text());
    if (!S_ISREG(existing_stat.st_mode))
      throw Error(shown + ": cannot rewrite in place: not a regular file");
    // Mode bits as well as access(): a privileged process passes access() on a read-only file.
    if ((existing_stat.st_mode & 0222) == 0 ||
        ::faccessat(AT_FDCWD, resolved.c_str(), W_OK, AT_EACCESS) != 0)
      throw Error(shown + ": the file is read-only; not rewritten (make it writable first)");
    if (existing_stat.st_nlink > 1)
      throw Error(shown + ": the file has " + std::to_string(existing_stat.st_nlink) +
                  " hard links; rewriting it would replace this name only and split it from the "
                  "others, so it is not rewritten (write to a new file instead)");
    target_ = resolved;
  }

  auto directory = target_.parent_path();
  if (directory.empty()) directory = ".";
  const std::string prefix = temporary_prefix(target_.filename().string());
  remove_stale_temporaries(directory, prefix);

  const std::string stem = (directory / prefix).string() + std::to_string(::getpid()) + "-";
  for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
    const std::string candidate = stem + random_suffix();
    SignalsBlocked blocked;
    // 0666: the kernel applies the umask, as for any new file. O_NOFOLLOW|O_EXCL: never opens or
    // follows what already sits at this name.
    fd_ = ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ >= 0) {
      temporary_ = candidate;
      slot_ = register_temporary(std::filesystem::absolute(temporary_).string());
    } else if (errno != EEXIST) {
      break;
    }
  }
  if (fd_ < 0)
    throw Error(shown + ": cannot create a temporary file in '" + directory.string() +
                "': " + errno_text());
  if (existing == Existing::rewrite_in_place) {
    // Owner and group first (chown clears set-id bits), then the mode; before any data is written.
    if (::fchown(fd_, existing_stat.st_uid, existing_stat.st_gid) != 0)
      (void)!::fchown(fd_, static_cast<uid_t>(-1), existing_stat.st_gid);
    if (::fchmod(fd_, existing_stat.st_mode & 07777) != 0)
      fail("cannot set the file mode: " + errno_text());
  }
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !temporary_.empty()) {
    SignalsBlocked blocked;
    ::unlink(temporary_.c_str());
    unregister_temporary(slot_);
  }
}

void AtomicFile::fail(const std::string& what) const {
  throw Error(target_.string() + ": " + what);
}

void AtomicFile::write(const void* data, std::size_t size) {
  const auto* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::write(fd_, bytes, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      fail("write failed: " + errno_text());
    }
    bytes += written;
    size -= static_cast<std::size_t>(written);
    appended_ += static_cast<std::uint64_t>(written);
  }
#ifdef SYNC_FILE_RANGE_WRITE
  // Starts writing each 8 MiB to disk as it is appended, without waiting: the disk then works
  // while the caller computes the rest, and commit()'s fsync finds little left to do (FLA-size
  // conversion: the fsync took ~45 ms of ~330). Advice only: errors surface at fsync.
  constexpr std::uint64_t kWritebackStep = std::uint64_t{8} << 20;
  if (appended_ - writeback_started_ >= kWritebackStep) {
    ::sync_file_range(fd_, static_cast<off_t>(writeback_started_),
                      static_cast<off_t>(appended_ - writeback_started_), SYNC_FILE_RANGE_WRITE);
    writeback_started_ = appended_;
  }
#endif
}

void AtomicFile::write_at(const void* data, std::size_t size, std::uint64_t offset) {
  const auto* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t written = ::pwrite(fd_, bytes, size, static_cast<off_t>(offset));
    if (written < 0) {
      if (errno == EINTR) continue;
      fail("write failed: " + errno_text());
    }
    bytes += written;
    offset += static_cast<std::uint64_t>(written);
    size -= static_cast<std::size_t>(written);
  }
}

void AtomicFile::commit() {
  if (::fsync(fd_) != 0) fail("fsync failed: " + errno_text());
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("write failed: " + errno_text());
  if (::rename(temporary_.c_str(), target_.c_str()) != 0)
    fail("cannot rename the finished file into place: " + errno_text());
  committed_ = true;
  unregister_temporary(slot_);
}

void set_stale_temporary_handler(std::function<void(const std::filesystem::path&)> handler) {
  std::lock_guard lock(g_handler_mutex);
  g_stale_handler = std::move(handler);
}

void remove_temporaries_on_signals() {
  for (int signal_number : kCleanupSignals) {
    struct sigaction current {};
    if (::sigaction(signal_number, nullptr, &current) != 0 || current.sa_handler == SIG_IGN)
      continue;
    struct sigaction action {};
    action.sa_handler = remove_temporaries_and_reraise;
    ::sigemptyset(&action.sa_mask);
    for (int other : kCleanupSignals) ::sigaddset(&action.sa_mask, other);
    ::sigaction(signal_number, &action, nullptr);
  }
}

bool process_has_ended(long pid) {
  if (pid <= 0 || pid > INT_MAX) return false;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

void check_output_is_not_input(const std::filesystem::path& output,
                               const std::vector<std::filesystem::path>& inputs) {
  struct stat out {};
  if (output.empty() || ::stat(output.c_str(), &out) != 0) return;  // a new file is no input
  for (const auto& input : inputs) {
    struct stat in {};
    if (input.empty() || ::stat(input.c_str(), &in) != 0) continue;
    if (in.st_dev == out.st_dev && in.st_ino == out.st_ino)
      throw Error(output.string() + ": is the same file as the input '" + input.string() +
                  "'; refusing to overwrite an input (choose another output)");
  }
}

void write_file_atomically(const std::filesystem::path& target, std::string_view content) {
  AtomicFile file(target);
  file.write(content);
  file.commit();
}

namespace {

namespace fs = std::filesystem;

// `p` absolute and normal, without a trailing separator: how two names of one place compare.
fs::path place_of(const fs::path& p) {
  auto normal = fs::absolute(p.empty() ? fs::path(".") : p).lexically_normal();
  return normal.has_filename() || normal == normal.root_path() ? normal : normal.parent_path();
}

bool is_a_directory(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

// Refuses a directory to make that exists as something else, or whose nearest existing ancestor
// is not a directory.
void check_directory_to_make(const fs::path& directory) {
  std::error_code ec;
  fs::path at = place_of(directory);
  while (!fs::exists(fs::symlink_status(at, ec)) && at.has_relative_path()) at = at.parent_path();
  if (!is_a_directory(at))
    throw Error(directory.string() + ": not a directory" +
                (at == place_of(directory) ? "" : " (" + at.string() + " is a file)"));
}

// The directories made for a set of files, removed again (when still empty) unless released.
class MadeDirectories {
 public:
  MadeDirectories(const MadeDirectories&) = delete;
  MadeDirectories& operator=(const MadeDirectories&) = delete;
  MadeDirectories() = default;
  ~MadeDirectories() {
    std::error_code ec;
    for (; !made_.empty(); made_.pop_back()) fs::remove(made_.back(), ec);  // innermost first
  }
  // Makes `directory` and its missing parents, outermost first.
  void make(const fs::path& directory) {
    std::vector<fs::path> missing;
    std::error_code ec;
    for (fs::path at = place_of(directory); !fs::exists(fs::symlink_status(at, ec));
         at = at.parent_path())
      missing.push_back(at);
    std::reverse(missing.begin(), missing.end());
    for (const auto& at : missing) {
      if (fs::create_directory(at, ec))
        made_.push_back(at);
      else if (ec)
        throw Error(directory.string() + ": cannot make the directory: " + ec.message());
    }
  }
  void release() { made_.clear(); }

 private:
  std::vector<fs::path> made_;
};

}  // namespace

void write_files_atomically(const std::vector<fs::path>& directories,
                            const std::vector<FileContent>& files) {
  std::set<fs::path> to_make, named;
  for (const auto& d : directories) {
    check_directory_to_make(d);
    to_make.insert(place_of(d));
  }
  for (const auto& f : files) {
    const std::string shown = f.path.string();
    if (!f.path.has_filename()) throw Error(shown + ": not a file name");
    if (is_a_directory(f.path)) throw Error(shown + ": is a directory");
    const auto directory = place_of(f.path).parent_path();
    if (!to_make.contains(directory) && !is_a_directory(directory))
      throw Error(shown + ": the directory " + f.path.parent_path().string() + " does not exist");
    if (!named.insert(place_of(f.path)).second) throw Error(shown + ": named twice");
  }
  MadeDirectories made;
  for (const auto& d : directories) made.make(d);
  std::vector<std::unique_ptr<AtomicFile>> staged;
  for (const auto& f : files) {
    staged.push_back(std::make_unique<AtomicFile>(f.path));
    staged.back()->write(f.content);
  }
  made.release();
  for (auto& file : staged) file->commit();
}

}  // namespace mosb
