#include "launch.hpp"

#include <fcntl.h>
#include <linux/capability.h>
#include <linux/close_range.h>
#include <net/if.h>
#include <sched.h>
#include <sys/ioctl.h>
#include <sys/mount.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <ctime>
#include <utility>

namespace mosb::run_internal {

rlimit started_file_limit{};

SealSetup::SealSetup(bool sealed, std::string directory, int network)
    : on(sealed),
      user_namespace(::geteuid() != 0),
      queries_directory(std::move(directory)),
      network_fd(network) {
  uid_map = std::to_string(::geteuid()) + " " + std::to_string(::geteuid()) + " 1";
  gid_map = std::to_string(::getegid()) + " " + std::to_string(::getegid()) + " 1";
}

bool read_exactly(int fd, void* data, std::size_t size, int flags) {
  auto* at = static_cast<char*>(data);
  while (size > 0) {
    const ssize_t got = ::recv(fd, at, size, flags);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) return false;
    at += got;
    size -= static_cast<std::size_t>(got);
  }
  return true;
}

[[noreturn]] void report_and_exit(int error_fd, int stage) {
  const ChildError report{stage, errno};
  if (error_fd >= 0) (void)!::write(error_fd, &report, sizeof report);
  ::_exit(127);
}

[[noreturn]] void execute(const char* executable, char* const argv[], int output, int errors,
                          int error_fd, int executable_fd) {
  ::dup2(output, 1);
  ::dup2(errors, 2);
  // Nothing but the standard streams reaches the program: not mosb's descriptors, nor any that
  // mosb inherited from whatever started it (a log opened by a wrapper would let a sealed solver
  // write outside its query). Close-on-exec, so that a failed exec can still report.
  if (::syscall(SYS_close_range, 3U, ~0U, CLOSE_RANGE_CLOEXEC) != 0) {
    const rlimit& files = started_file_limit;  // before Linux 5.11: the numbers mosb started with
    const int last =
        files.rlim_cur > 0 && files.rlim_cur < 65536 ? static_cast<int>(files.rlim_cur) : 65536;
    for (int fd = 3; fd < last; ++fd) ::fcntl(fd, F_SETFD, FD_CLOEXEC);
  }
  if (started_file_limit.rlim_max != 0) ::setrlimit(RLIMIT_NOFILE, &started_file_limit);
  if (executable_fd >= 0)
    ::fexecve(executable_fd, argv, environ);
  else
    ::execve(executable, argv, environ);
  report_and_exit(error_fd, 2);
}

bool write_exactly(int fd, const void* data, std::size_t count) {
  const auto* at = static_cast<const char*>(data);
  while (count > 0) {
    const ssize_t put = ::send(fd, at, count, MSG_NOSIGNAL);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) return false;
    at += put;
    count -= static_cast<std::size_t>(put);
  }
  return true;
}

bool send_with_descriptors(int socket, const void* data, std::size_t size, const int* fds,
                           std::size_t count) {
  iovec part{const_cast<void*>(data), size};
  msghdr message{};
  message.msg_iov = &part;
  message.msg_iovlen = 1;
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int) * kMaxDescriptors)];
  if (count > kMaxDescriptors) {
    errno = EINVAL;
    return false;
  }
  if (count > 0) {
    message.msg_control = control;
    message.msg_controllen = CMSG_SPACE(sizeof(int) * count);
    cmsghdr* c = CMSG_FIRSTHDR(&message);
    c->cmsg_level = SOL_SOCKET;
    c->cmsg_type = SCM_RIGHTS;
    c->cmsg_len = CMSG_LEN(sizeof(int) * count);
    std::memcpy(CMSG_DATA(c), fds, sizeof(int) * count);
  }
  ssize_t put = 0;
  while ((put = ::sendmsg(socket, &message, MSG_NOSIGNAL)) < 0 && errno == EINTR) {
  }
  if (put < 0) return false;
  const auto sent = static_cast<std::size_t>(put);
  return sent == size || write_exactly(socket, static_cast<const char*>(data) + sent, size - sent);
}

ssize_t receive_with_descriptors(int socket, void* data, std::size_t size, int* fds,
                                 std::size_t& count) {
  iovec part{data, size};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(int) * kMaxDescriptors)];
  msghdr message{};
  message.msg_iov = &part;
  message.msg_iovlen = 1;
  message.msg_control = control;
  message.msg_controllen = sizeof control;
  ssize_t got = 0;
  while ((got = ::recvmsg(socket, &message, MSG_CMSG_CLOEXEC)) < 0 && errno == EINTR) {
  }
  std::size_t received = 0;
  for (cmsghdr* c = CMSG_FIRSTHDR(&message); got >= 0 && c != nullptr; c = CMSG_NXTHDR(&message, c))
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_RIGHTS)
      for (std::size_t i = 0; i < (c->cmsg_len - CMSG_LEN(0)) / sizeof(int); ++i) {
        int fd = -1;
        std::memcpy(&fd, CMSG_DATA(c) + i * sizeof(int), sizeof fd);
        if (received < count)
          fds[received++] = fd;
        else
          ::close(fd);
      }
  count = received;
  return got;
}

namespace {

// In a forked child: `text` written to the kernel file `path`.
bool write_kernel_file(const char* path, const std::string& text) {
  const int fd = ::open(path, O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  return written;
}

}  // namespace

bool loopback_up() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  ifreq request{};
  std::memcpy(request.ifr_name, "lo", 3);
  request.ifr_flags = IFF_UP | IFF_RUNNING;
  const bool up = ::ioctl(fd, SIOCSIFFLAGS, &request) == 0;
  ::close(fd);
  return up;
}

bool seal_namespaces(SealSetup& s) {
  if (s.user_namespace) {
    if (::unshare(CLONE_NEWUSER | CLONE_NEWNS | CLONE_NEWNET) != 0 ||
        !write_kernel_file("/proc/self/setgroups", "deny") ||
        !write_kernel_file("/proc/self/uid_map", s.uid_map) ||
        !write_kernel_file("/proc/self/gid_map", s.gid_map))
      return false;
  } else if (s.network_fd >= 0) {
    if (::unshare(CLONE_NEWNS) != 0 || ::setns(s.network_fd, CLONE_NEWNET) != 0) return false;
  } else if (::unshare(CLONE_NEWNS | CLONE_NEWNET) != 0) {
    return false;
  }
  if (::mount(nullptr, "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0) return false;
  mount_attr read_only{};
  read_only.attr_set = MOUNT_ATTR_RDONLY | MOUNT_ATTR_NOSUID;
  if (::mount_setattr(AT_FDCWD, "/", AT_RECURSIVE, &read_only, sizeof read_only) != 0) return false;
  if (::access("/dev/shm", F_OK) == 0 &&
      ::mount("tmpfs", "/dev/shm", "tmpfs", MS_NOSUID | MS_NODEV, "mode=1777") != 0)
    return false;
  // Opened in the new namespace: open_tree clones only a mount of the caller's own namespace.
  s.queries_fd = ::open(s.queries_directory.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
  return s.queries_fd >= 0 && (s.network_fd >= 0 || loopback_up());
}

namespace {

// Every capability dropped, for good: a solver run by root cannot undo its seal (remount, unshare,
// trace mosb). Async-signal-safe.
bool drop_capabilities() {
  for (int capability = 0; capability < 64; ++capability)
    ::prctl(PR_CAPBSET_DROP, capability, 0, 0, 0);  // EINVAL past the kernel's last: nothing
  __user_cap_header_struct header{_LINUX_CAPABILITY_VERSION_3, 0};
  std::array<__user_cap_data_struct, 2> none{};
  return ::syscall(SYS_capset, &header, none.data()) == 0 &&
         ::prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0) == 0;
}

// In the solver's process, once its command is known: the query's directory (that of its stdout
// file, a subdirectory of the queries directory) writable at its place, then every capability
// dropped. Async-signal-safe.
bool open_query_directory(const SealSetup& s, const char* stdout_path) {
  std::array<char, 4096> directory{};
  const std::size_t length = std::strlen(stdout_path);
  if (length >= directory.size()) {
    errno = ENAMETOOLONG;
    return false;
  }
  std::memcpy(directory.data(), stdout_path, length + 1);
  char* slash = std::strrchr(directory.data(), '/');
  if (slash == nullptr || slash == directory.data()) {
    errno = EINVAL;
    return false;
  }
  *slash = '\0';
  const char* name = std::strrchr(directory.data(), '/') + 1;
  const int tree = ::open_tree(s.queries_fd, name, OPEN_TREE_CLONE | OPEN_TREE_CLOEXEC);
  if (tree < 0) return false;
  mount_attr writable{};
  writable.attr_clr = MOUNT_ATTR_RDONLY;
  const bool attached =
      ::mount_setattr(tree, "", AT_EMPTY_PATH, &writable, sizeof writable) == 0 &&
      ::move_mount(tree, "", AT_FDCWD, directory.data(), MOVE_MOUNT_F_EMPTY_PATH) == 0;
  const int error = errno;
  ::close(tree);
  errno = error;
  return attached && drop_capabilities();
}

// The pids listed in /proc/thread-self/children, killed; whether any was. Async-signal-safe: one
// read into a stack buffer (a longer list is killed over several rounds).
bool kill_listed_children() {
  const int fd = ::open("/proc/thread-self/children", O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  char text[4096];
  const ssize_t size = ::read(fd, text, sizeof text);
  ::close(fd);
  bool any = false;
  long pid = 0;
  for (ssize_t i = 0; i < size; ++i) {
    if (text[i] >= '0' && text[i] <= '9') {
      pid = pid * 10 + (text[i] - '0');
    } else {
      if (pid > 0) any = ::kill(static_cast<pid_t>(pid), SIGKILL) == 0 || any;
      pid = 0;
    }
  }
  if (pid > 0) any = ::kill(static_cast<pid_t>(pid), SIGKILL) == 0 || any;
  return any;
}

// In the launcher, once the solver has been reaped: kills and reaps every process left of the
// query. In a PID namespace the launcher is its init, and kill(-1) reaches every process of it;
// a subreaper kills its children, whose own children then become its children, round after
// round. Returns whether anything was left. Async-signal-safe.
bool kill_what_is_left(bool pid_namespace) {
  bool left = false;
  for (int round = 0; round < 10000; ++round) {
    int status = 0;
    pid_t reaped = 0;
    while ((reaped = ::waitpid(-1, &status, WNOHANG)) > 0) {
    }
    if (reaped < 0 && errno == ECHILD) return left;  // nothing left: the usual case, at once
    left = true;
    if (pid_namespace)
      ::kill(-1, SIGKILL);
    else
      kill_listed_children();
    ::waitpid(-1, &status, 0);
  }
  return left;
}

// Where the solver's process receives its command: one per parked child, each a copy of the fork
// server's, untouched there, so the child alone pays for the pages it writes. A command that does
// not fit is not started.
char launch_bytes[kLaunchBytes];
char* launch_words[kLaunchWords];

// The command's header, and with it the descriptor of the executable when it has one (then
// `executable_fd` is that descriptor here, else -1).
bool receive_header(int command_fd, LaunchHeader& header) {
  int received = -1;
  std::size_t count = 1;
  const ssize_t got =
      receive_with_descriptors(command_fd, &header, sizeof header, &received, count);
  if (got <= 0) return false;
  const auto have = static_cast<std::size_t>(got);
  if (have < sizeof header &&
      !read_exactly(command_fd, reinterpret_cast<char*>(&header) + have, sizeof header - have))
    return false;
  if (header.executable_fd != 0 && received < 0) return false;
  header.executable_fd = header.executable_fd != 0 ? received : -1;
  return true;
}

// The solver's process, forked by the launcher while the previous query still runs: a process
// group of its own (the watchdog's signals reach its tree and not the launcher), says it is ready
// (mosb learns its pid, in mosb's PID namespace, from the message's credentials), waits for its
// command and executes it. It runs in the launcher's memory until it executes (vfork, see
// launcher) and writes only the launch buffer and its own stack there.
[[noreturn]] void solver_child(int command_fd, int error_fd, const SealSetup& seal) {
  ::setpgid(0, 0);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0);  // the launcher's end is the solver's
  const char ready = 1;
  if (::send(command_fd, &ready, 1, MSG_NOSIGNAL) != 1) ::_exit(127);
  LaunchHeader header;
  if (!receive_header(command_fd, header) || header.size > kLaunchBytes ||
      !read_exactly(command_fd, launch_bytes, header.size))
    ::_exit(127);  // mosb gave up on this child
  char* text = launch_bytes;
  char* const end = text + header.size;
  std::size_t count = 0;
  while (text < end && count + 1 < kLaunchWords) {
    launch_words[count++] = text;
    while (text < end && *text != '\0') ++text;
    ++text;
  }
  if (count < 4) ::_exit(127);
  const char* executable = launch_words[0];
  char** argv = launch_words + 3;
  launch_words[count] = nullptr;

  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
  ::signal(SIGPIPE, SIG_DFL);
  if (header.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(header.cpu, &set);
    ::sched_setaffinity(0, sizeof set, &set);
  }
  if (header.rlimit_as != 0) {
    const rlimit limit{header.rlimit_as, header.rlimit_as};
    ::setrlimit(RLIMIT_AS, &limit);
  }
  if (seal.on && !open_query_directory(seal, launch_words[1])) report_and_exit(error_fd, 6);
  // Exclusively: a file that exists is another query's, and never this one's output. Closed on
  // exec: the solver holds them as its standard output and error only.
  const int output = ::open(launch_words[1], O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  const int errors = ::open(launch_words[2], O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (output < 0 || errors < 0) report_and_exit(error_fd, 3);
  execute(executable, argv, output, errors, error_fd, header.executable_fd);
}

// The launcher of one query: forks the solver's process, reaps it (and meanwhile any orphan
// reparented here), kills what the solver left, tells mosb how the solver ended, and exits.
[[noreturn]] void launcher(int command_fd, int error_fd, bool pid_namespace,
                           const SealSetup& seal) {
  // A sealed query's processes see their PID namespace alone in /proc, read-only: not mosb's
  // memory, not another query's processes.
  if (seal.on && pid_namespace &&
      ::mount("proc", "/proc", "proc", MS_RDONLY | MS_NOSUID | MS_NODEV | MS_NOEXEC, nullptr) != 0)
    report_and_exit(error_fd, 6);
  // vfork: the solver's process shares this memory until it executes, so its execve has no copy
  // to tear down. The launcher has nothing to do before the solver executes anyway. The analyzer
  // allows only exec or _exit after vfork: solver_child also makes other async-signal-safe system
  // calls, below the launcher's stack frame, writes only the launch buffer and never returns.
  const pid_t solver = ::vfork();  // NOLINT(clang-analyzer-security.insecureAPI.vfork)
  if (solver < 0) report_and_exit(error_fd, 5);
  if (solver == 0) solver_child(command_fd, error_fd, seal);  // NOLINT(clang-analyzer-unix.Vfork)
  // Here the solver's process has executed (or ended): from now on its memory is the solver's,
  // not this one's, and mosb starts watching it.
  const char executed = 1;
  write_exactly(command_fd, &executed, 1);
  LauncherReport report;
  rusage usage{};
  while (true) {
    int status = 0;
    const pid_t reaped = ::wait4(-1, &status, 0, &usage);
    if (reaped == solver) {
      report.status = status;
      report.max_rss_kb = usage.ru_maxrss;
      break;
    }
    if (reaped < 0 && errno != EINTR) ::_exit(127);
  }
  report.leftovers = kill_what_is_left(pid_namespace) ? 1 : 0;
  rusage reaped{};
  ::getrusage(RUSAGE_CHILDREN, &reaped);
  report.cpu_microseconds = (reaped.ru_utime.tv_sec + reaped.ru_stime.tv_sec) * 1000000 +
                            reaped.ru_utime.tv_usec + reaped.ru_stime.tv_usec;
  timespec now{};
  ::clock_gettime(CLOCK_MONOTONIC, &now);
  report.sent_nanoseconds = std::int64_t{now.tv_sec} * 1000000000 + now.tv_nsec;
  write_exactly(command_fd, &report, sizeof report);
  ::_exit(0);
}

}  // namespace

[[noreturn]] void parked_child(int command_fd, int error_fd, int procs_fd, pid_t mosb,
                               bool pid_namespace, SealSetup& seal) {
  // A process group, not a session: on Linux a new session is a new scheduler autogroup, which
  // costs time per query and gives the solver another CPU share than a shell loop gives it.
  ::setpgid(0, 0);
  // A kill -9 of mosb run takes the launcher with it, and the launcher's end the solver's; a
  // mosb that ended before the signal was asked for has left this child to another parent.
  ::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0);
  if (::getppid() != mosb) ::_exit(127);
  // mosb's standard streams are not the solver's: a waiting child holds none of them open.
  const int null = ::open("/dev/null", O_RDWR);
  if (null < 0) report_and_exit(error_fd, 3);
  for (int fd = 0; fd < 3; ++fd) ::dup2(null, fd);
  if (null > 2) ::close(null);
  if (procs_fd >= 0 && ::write(procs_fd, "0", 1) != 1) report_and_exit(error_fd, 1);
  if (seal.on && !seal_namespaces(seal)) report_and_exit(error_fd, 6);
  // The watchdog's SIGTERM is for the solver: the launcher waits for its end (the solver
  // unblocks them before it executes).
  sigset_t stops;
  sigemptyset(&stops);
  for (const int signal : {SIGTERM, SIGINT, SIGHUP}) sigaddset(&stops, signal);
  ::sigprocmask(SIG_BLOCK, &stops, nullptr);
  if (!pid_namespace) {
    ::prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0);
    launcher(command_fd, error_fd, pid_namespace, seal);
  }
  if (::unshare(CLONE_NEWPID) != 0) report_and_exit(error_fd, 4);
  const pid_t init = ::fork();  // the namespace's first process, its init
  if (init < 0) report_and_exit(error_fd, 5);
  if (init == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0);
    launcher(command_fd, error_fd, pid_namespace, seal);
  }
  ::close(command_fd);
  int status = 0;
  while (::waitpid(init, &status, 0) < 0 && errno == EINTR) {
  }
  ::_exit(0);
}

}  // namespace mosb::run_internal
