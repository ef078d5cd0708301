#include "process.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <mutex>
#include <sstream>
#include <thread>
#include <utility>

#include "fork_server_image.hpp"
#include "launch.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/read_file.hpp"

namespace mosb {

std::string_view to_string(Measurement m) {
  return kMeasurementNames.name(m);
}

std::optional<Measurement> parse_measurement(std::string_view text) {
  return kMeasurementNames.parse(text);
}

namespace run_internal {

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kPollMilliseconds = 20;

std::string errno_text(int error) {
  return std::strerror(error);
}

[[noreturn]] void fail(const std::string& what) {
  throw Error(ErrorCode::io, what + ": " + errno_text(errno));
}

// The memory cgroup (v1) directory of this process, from /proc/self/cgroup.
std::string own_memory_cgroup() {
  std::ifstream in("/proc/self/cgroup");
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    std::stringstream list(controllers);
    for (std::string c; std::getline(list, c, ',');)
      if (c == "memory") {
        const std::string path = line.substr(second + 1);
        return "/sys/fs/cgroup/memory" + (path == "/" ? std::string() : path);
      }
  }
  return {};
}

bool write_file(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  return ok;
}

// A cgroup or /proc file's text; empty when it cannot be read (a file this kernel does not have
// is no figure, a process that has ended has no usage: neither is an error).
std::string read_kernel_file(const std::string& path) {
  try {
    return read_whole_file(path);
  } catch (const Error&) {
    return {};
  }
}

// The value of `key` in a "key value" per line file (memory.oom_control), 0 when absent.
std::uint64_t keyed_value(const std::string& text, std::string_view key) {
  std::stringstream in(text);
  std::string k;
  std::uint64_t v = 0;
  while (in >> k >> v)
    if (k == key) return v;
  return 0;
}

std::vector<pid_t> cgroup_members(const std::string& dir) {
  std::vector<pid_t> pids;
  std::ifstream in(dir + "/cgroup.procs");
  for (long pid = 0; in >> pid;) pids.push_back(static_cast<pid_t>(pid));
  return pids;
}

}  // namespace

Measurement detect_measurement() {
  const std::string base = own_memory_cgroup();
  if (base.empty() || ::access((base + "/memory.limit_in_bytes").c_str(), W_OK) != 0)
    return Measurement::rlimit_poll;
  const std::string probe = base + "/mosb-probe-" + std::to_string(::getpid());
  if (::mkdir(probe.c_str(), 0700) != 0) return Measurement::rlimit_poll;
  ::rmdir(probe.c_str());
  return Measurement::cgroup_v1;
}

Isolation detect_isolation() {
  const pid_t probe = ::fork();
  if (probe < 0) return Isolation::subreaper;
  if (probe == 0) ::_exit(::unshare(CLONE_NEWPID) == 0 ? 0 : 1);
  int status = 0;
  while (::waitpid(probe, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? Isolation::pid_namespace
                                                       : Isolation::subreaper;
}

std::string describe_measurement(Measurement m) {
  const std::string time =
      "wall: steady clock from the command to the launcher's report that the solver was reaped; "
      "cpu: user+system of the solver and every descendant reaped (getrusage)";
  if (m == Measurement::cgroup_v1)
    return time +
           "; memory: cgroup v1 memory controller, one group per query (memory.limit_in_bytes "
           "and memory.memsw.limit_in_bytes limit, memory.max_usage_in_bytes is the peak, "
           "page cache included; an OOM kill in the group is memory-limit)";
  return time +
         "; memory: RLIMIT_AS per process, and the resident set summed over the query's "
         "processes (the launcher's descendants) polled every 20 ms (peak = largest sum; a sum "
         "over the limit is memory-limit)";
}

namespace {

// Groups `mosb-run-PID-JOB` left by a mosb run that was killed (kill -9 leaves its groups and the
// solver's descendants behind): when PID no longer runs, what is left in the group is killed and
// the group removed.
void remove_stale_groups() {
  const std::string base = own_memory_cgroup();
  if (base.empty()) return;
  DIR* dir = ::opendir(base.c_str());
  if (!dir) return;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string name = entry->d_name;
    if (!name.starts_with("mosb-run-")) continue;
    const long pid = std::atol(name.c_str() + 9);
    if (pid <= 0 || pid == ::getpid() || ::kill(static_cast<pid_t>(pid), 0) == 0) continue;
    const std::string group = base + "/" + name;
    for (int i = 0; i < 100 && ::rmdir(group.c_str()) != 0 && errno == EBUSY; ++i) {
      for (const pid_t member : cgroup_members(group)) ::kill(member, SIGKILL);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  ::closedir(dir);
}

}  // namespace

void prepare_process_runner() {
  remove_stale_groups();
  ::prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0);
  // Once per process: a later run (an experiment runs many) finds the limit raised already.
  if (started_file_limit.rlim_max != 0 || ::getrlimit(RLIMIT_NOFILE, &started_file_limit) != 0)
    return;
  const rlimit raised{started_file_limit.rlim_max, started_file_limit.rlim_max};
  ::setrlimit(RLIMIT_NOFILE, &raised);
}

namespace {

// What the processes of one query use now: the resident set summed, and the CPU time summed with
// that of the children each has reaped.
struct QueryUsage {
  std::uint64_t rss_bytes = 0;
  double cpu_seconds = 0;
};

// The children of every thread of `pid` (/proc/PID/task/TID/children), appended to `out`.
void append_children(pid_t pid, std::vector<pid_t>& out) {
  const std::string tasks_dir = "/proc/" + std::to_string(pid) + "/task";
  DIR* tasks = ::opendir(tasks_dir.c_str());
  if (!tasks) return;
  while (const dirent* entry = ::readdir(tasks)) {
    if (entry->d_name[0] < '0' || entry->d_name[0] > '9') continue;
    const std::string list = read_kernel_file(tasks_dir + "/" + entry->d_name + "/children");
    const char* at = list.c_str();
    char* next = nullptr;
    for (long child = std::strtol(at, &next, 10); next != at; child = std::strtol(at, &next, 10)) {
      out.push_back(static_cast<pid_t>(child));
      at = next;
    }
  }
  ::closedir(tasks);
}

// The usage of the query's processes: the descendants of `root` (mosb's PID numbers) from
// `first_level` down (1: its children), found every 20 ms through the children lists, so a process
// that left the solver's process group or session is still counted. The resident set comes from
// /proc/PID/statm; the CPU time, only when `with_cpu`, from /proc/PID/stat, whose reading of a
// running process's time takes that process's run-queue lock.
QueryUsage query_usage(pid_t root, int first_level, bool with_cpu) {
  static const long page = ::sysconf(_SC_PAGESIZE);
  static const double tick = 1.0 / static_cast<double>(::sysconf(_SC_CLK_TCK));
  QueryUsage usage;
  std::vector<pid_t> level, next;
  append_children(root, level);
  for (int depth = 1; !level.empty(); ++depth) {
    next.clear();
    for (const pid_t pid : level) {
      append_children(pid, next);
      if (depth < first_level) continue;
      const std::string proc = "/proc/" + std::to_string(pid);
      // "size resident shared ...", in pages
      const std::string statm = read_kernel_file(proc + "/statm");
      const char* resident = std::strchr(statm.c_str(), ' ');
      const long pages = resident ? std::strtol(resident + 1, nullptr, 10) : 0;
      if (pages > 0) usage.rss_bytes += static_cast<std::uint64_t>(pages) * page;
      if (!with_cpu) continue;
      // After "pid (comm)": fields 14-17 are utime stime cutime cstime (clock ticks).
      const std::string stat = read_kernel_file(proc + "/stat");
      const char* field = std::strrchr(stat.c_str(), ')');
      long ticks = 0;
      for (int i = 3; field && i <= 17; ++i) {
        field = std::strchr(field + 1, ' ');
        if (field && i >= 14) ticks += std::strtol(field + 1, nullptr, 10);
      }
      if (ticks > 0) usage.cpu_seconds += static_cast<double>(ticks) * tick;
    }
    level.swap(next);
  }
  return usage;
}

// A memory cgroup for one solver, removed when the object ends.
class MemoryGroup {
 public:
  MemoryGroup(const std::string& name, std::uint64_t limit) {
    dir_ = own_memory_cgroup() + "/" + name;
    if (::mkdir(dir_.c_str(), 0700) != 0 && errno != EEXIST) fail(dir_ + ": cannot create");
    if (limit != 0) {
      if (!write_file(dir_ + "/memory.limit_in_bytes", std::to_string(limit)))
        fail(dir_ + "/memory.limit_in_bytes: cannot set the limit");
      // With swap accounting, memory+swap gets the same limit: no escape into swap.
      write_file(dir_ + "/memory.memsw.limit_in_bytes", std::to_string(limit));
    }
    // The figures are opened now, ahead of the query, and read once it has ended, on the path to
    // the next one. A file that cannot be opened (too many open files) fails the run: a query
    // without them would lose its peak and its memory-limit status.
    const auto open_file = [this](File which, const char* file, int flags) {
      const std::string path = dir_ + "/" + file;
      fds_[which] = ::open(path.c_str(), flags | O_CLOEXEC);
      if (fds_[which] < 0) {
        const int error = errno;
        close_all();
        ::rmdir(dir_.c_str());
        errno = error;
        fail(path + ": cannot open");
      }
    };
    open_file(kProcs, "cgroup.procs", O_WRONLY);
    open_file(kMaxUsage, "memory.max_usage_in_bytes", O_RDONLY);
    open_file(kOomControl, "memory.oom_control", O_RDONLY);
    open_file(kFailCount, "memory.failcnt", O_RDONLY);
  }
  // Removing the group is also the test that nothing is left in it (EBUSY): its member list is
  // read only when something is, and then every 10 ms, since every read of a v1 group's list costs
  // milliseconds. The removal is tried every millisecond: a killed child's processes leave the
  // group within a few (up to 2 s in all).
  ~MemoryGroup() {
    close_all();
    for (int i = 0; i < 2000 && ::rmdir(dir_.c_str()) != 0 && errno == EBUSY; ++i) {
      if (i % 10 == 0) kill_all();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  MemoryGroup(const MemoryGroup&) = delete;
  MemoryGroup& operator=(const MemoryGroup&) = delete;

  // The child writes "0" here (itself) before it executes: no round trip through the parent.
  int procs_fd() const { return fds_[kProcs]; }
  void kill_all() const {
    for (const pid_t pid : cgroup_members(dir_)) ::kill(pid, SIGKILL);
  }
  std::optional<std::uint64_t> peak() const { return number(kMaxUsage); }
  bool oom_killed() const {
    const std::string oom = figure(kOomControl);
    return keyed_value(oom, "oom_kill") > 0 || keyed_value(oom, "under_oom") > 0;
  }
  bool hit_limit() const { return number(kFailCount).value_or(0) > 0; }

 private:
  enum File : std::size_t { kProcs, kMaxUsage, kOomControl, kFailCount, kFiles };
  // The figure's text now: a control file is generated afresh by each read from offset 0. Empty
  // when it cannot be read.
  std::string figure(File which) const {
    char text[512];
    const ssize_t size = ::pread(fds_[which], text, sizeof text, 0);
    return size > 0 ? std::string(text, static_cast<std::size_t>(size)) : std::string();
  }
  std::optional<std::uint64_t> number(File which) const {
    const std::string text = figure(which);
    if (text.empty()) return std::nullopt;
    return std::strtoull(text.c_str(), nullptr, 10);
  }
  void close_all() {
    for (int& fd : fds_)
      if (fd >= 0) ::close(std::exchange(fd, -1));
  }

  std::string dir_;
  std::array<int, kFiles> fds_{-1, -1, -1, -1};  // by File, -1 when not open
};

// In the parent, right after fork() returned `pid`: closes the child's ends of their pipes, and
// when the fork failed also the parent's ends, and throws.
void in_parent_after_fork(pid_t pid, std::initializer_list<int> child_ends,
                          std::initializer_list<int> parent_ends) {
  const int fork_error = errno;
  for (const int fd : child_ends) ::close(fd);
  if (pid >= 0) return;
  for (const int fd : parent_ends) ::close(fd);
  errno = fork_error;
  fail("cannot fork");
}

// Waits for the child `pid` to end, through interruptions by signals: its wait status, and its
// resource use into `usage` when given.
int wait_for(pid_t pid, rusage* usage = nullptr) {
  int status = 0;
  while (::wait4(pid, &status, 0, usage) < 0 && errno == EINTR) {
  }
  return status;
}

double seconds_of(const timeval& t) {
  return static_cast<double>(t.tv_sec) + t.tv_usec / 1e6;
}

// A backstop after the launcher's own cleanup: kills everything left of the solver's process group
// and reaps what became ours (a launcher killed from outside leaves its orphans to mosb run).
void kill_leftovers(pid_t pgid, ProcessOutcome& out) {
  const auto until = Clock::now() + std::chrono::seconds(5);
  while (true) {
    ::kill(-pgid, SIGKILL);
    int status = 0;
    rusage usage{};
    while (::wait4(-pgid, &status, WNOHANG, &usage) > 0)
      out.cpu_seconds += seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime);
    if (::kill(-pgid, 0) != 0 && errno == ESRCH) return;
    if (Clock::now() > until) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

// RLIMIT_AS under rlimit_poll: twice the limit, a backstop for allocations faster than the poll.
// The address space of a process exceeds its resident memory (libraries, reserved arenas), so the
// limit itself would refuse solvers well below it; the poll enforces the limit on resident memory.
std::uint64_t rlimit_backstop(std::uint64_t memory) {
  return memory == 0 ? 0 : memory > (UINT64_MAX / 2) ? memory : memory * 2;
}

// The child's report of a failed start, read once it has ended (nothing: it executed).
std::optional<ChildError> child_error(int fd) {
  ChildError report;
  const ssize_t got = ::read(fd, &report, sizeof report);
  if (got != sizeof report) return std::nullopt;
  return report;
}

// The fork server's program (fork_server.cpp) in a sealed memory file, made once per process and
// opened read-only (a file open for writing cannot be executed): the path that executes it.
const std::string& fork_server_program() {
  static const std::string path = [] {
    // MFD_EXEC (Linux 6.3, not in these headers): executable even where vm.memfd_noexec makes
    // memory files non-executable by default; an older kernel refuses the flag (EINVAL).
    constexpr unsigned kExecutable = 0x10;
    int image = ::memfd_create("mosb-fork-server", MFD_CLOEXEC | MFD_ALLOW_SEALING | kExecutable);
    if (image < 0 && errno == EINVAL)
      image = ::memfd_create("mosb-fork-server", MFD_CLOEXEC | MFD_ALLOW_SEALING);
    if (image < 0) fail("cannot create the fork server's memory file");
    const auto size = static_cast<std::size_t>(mosb_fork_server_image_end - mosb_fork_server_image);
    std::size_t done = 0;
    while (done < size) {
      const ssize_t put = ::write(image, mosb_fork_server_image + done, size - done);
      if (put < 0 && errno == EINTR) continue;
      if (put <= 0) break;
      done += static_cast<std::size_t>(put);
    }
    const bool written =
        done == size &&
        ::fcntl(image, F_ADD_SEALS, F_SEAL_SEAL | F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_WRITE) == 0;
    const int program =
        written ? ::open(("/proc/self/fd/" + std::to_string(image)).c_str(), O_RDONLY | O_CLOEXEC)
                : -1;
    const int error = errno;
    ::close(image);
    errno = error;
    if (program < 0) fail("cannot write the fork server's memory file");
    return "/proc/self/fd/" + std::to_string(program);
  }();
  return path;
}

}  // namespace

// mosb's end of one fork server (launch.hpp), started by the runner that uses it, from its thread
// (the thread that forks a child is the one whose end the child's PR_SET_PDEATHSIG watches),
// and ended with it.
class ForkServer {
 public:
  ForkServer() {
    int ends[2];
    if (::socketpair(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0, ends) != 0)
      fail("cannot create a socket pair");
    socket_ = ends[0];
    posix_spawn_file_actions_t actions;
    posix_spawnattr_t attributes;
    ::posix_spawn_file_actions_init(&actions);
    ::posix_spawn_file_actions_adddup2(&actions, ends[1], 3);
    ::posix_spawnattr_init(&attributes);
    // A process group of its own, like the children: a Ctrl-C on the terminal reaches mosb alone.
    ::posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    ::posix_spawnattr_setpgroup(&attributes, 0);
    const std::string mosb = std::to_string(::getpid());
    const std::string soft = std::to_string(started_file_limit.rlim_cur);
    const std::string hard = std::to_string(started_file_limit.rlim_max);
    const std::string& program = fork_server_program();
    char name[] = "mosb-fork-server";
    char* argv[] = {name, const_cast<char*>(mosb.c_str()), const_cast<char*>(soft.c_str()),
                    const_cast<char*>(hard.c_str()), nullptr};
    const int error = ::posix_spawn(&pid_, program.c_str(), &actions, &attributes, argv, environ);
    ::posix_spawn_file_actions_destroy(&actions);
    ::posix_spawnattr_destroy(&attributes);
    ::close(ends[1]);
    if (error != 0) {
      ::close(socket_);
      errno = error;
      fail("cannot start the fork server");
    }
  }
  // The socket's end is the server's.
  ~ForkServer() {
    ::close(socket_);
    wait_for(pid_);
  }
  ForkServer(const ForkServer&) = delete;
  ForkServer& operator=(const ForkServer&) = delete;

  // A parked child for `request` with the descriptors of ParkRequest's order: its pid, or -1 with
  // errno set.
  pid_t park(const ParkRequest& request, const std::string& directory,
             const std::vector<int>& fds) {
    if (directory.size() > kMaxDirectory) {
      errno = ENAMETOOLONG;
      return -1;
    }
    std::string bytes(reinterpret_cast<const char*>(&request), sizeof request);
    bytes += directory;
    // One message (a SOCK_SEQPACKET socket): a request is never split.
    if (!send_with_descriptors(socket_, bytes.data(), bytes.size(), fds.data(), fds.size()))
      return -1;
    ParkReply reply;
    if (!read_exactly(socket_, &reply, sizeof reply)) {
      errno = EPIPE;  // the server has ended
      return -1;
    }
    errno = reply.error;
    return reply.pid;
  }

 private:
  int socket_ = -1;
  pid_t pid_ = -1;
};

// A forked child waiting in its memory group for the command of the next query (parked_child).
struct ProcessRunner::Parked {
  pid_t pid = -1;       // the parked child (in a PID namespace: the launcher's parent)
  pid_t solver = -1;    // the solver's process, in mosb's PID namespace (from wait_ready)
  int command_fd = -1;  // mosb's end of the socket pair: ready byte in, command out, report in
  int error_fd = -1;    // read end of the child's error pipe
  std::unique_ptr<MemoryGroup> group;
  Measurement m = Measurement::rlimit_poll;
  std::uint64_t memory = 0;
  std::string group_prefix;
  Isolation isolation = Isolation::subreaper;
  bool sealed = false;
  std::string queries_directory;
  bool launched = false;
  bool executed = false;  // the launcher's byte saying the solver's process executed was read
  bool reaped = false;
  // Readable when the child has ended (-1: this kernel has no pidfd_open; the query then ends on
  // the child's end alone).
  int pidfd = -1;

  Parked(ForkServer& server, Measurement measurement, std::uint64_t memory_bytes,
         const ProcessSpec& spec, std::uint64_t sequence, int network_fd)
      : m(measurement),
        memory(memory_bytes),
        group_prefix(spec.group_name),
        isolation(spec.isolation),
        sealed(spec.seal == Seal::sealed),
        queries_directory(spec.queries_directory) {
    const auto& prefix = group_prefix;
    if (m == Measurement::cgroup_v1)
      group = std::make_unique<MemoryGroup>(prefix + "-" + std::to_string(sequence), memory);
    int command[2], error[2];
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, command) != 0)
      fail("cannot create a socket pair");
    // The solver's ready byte then carries its pid as mosb's namespace numbers it.
    const int on = 1;
    ::setsockopt(command[1], SOL_SOCKET, SO_PASSCRED, &on, sizeof on);
    // Non-blocking: read after the child ended, when a sibling forked meanwhile may still hold the
    // write end (until it executes).
    if (::pipe2(error, O_CLOEXEC) != 0) {
      ::close(command[0]);
      ::close(command[1]);
      fail("cannot create a pipe");
    }
    ::fcntl(error[0], F_SETFL, O_NONBLOCK);
    ParkRequest request;
    request.pid_namespace = isolation == Isolation::pid_namespace ? 1 : 0;
    request.sealed = sealed ? 1 : 0;
    request.directory_size = static_cast<std::uint32_t>(queries_directory.size());
    std::vector<int> fds{command[0], error[1]};
    if (group) {
      request.has_procs = 1;
      fds.push_back(group->procs_fd());
    }
    if (sealed && network_fd >= 0) {
      request.has_network = 1;
      fds.push_back(network_fd);
    }
    pid = server.park(request, queries_directory, fds);
    in_parent_after_fork(pid, {command[0], error[1]}, {command[1], error[0]});
    command_fd = command[1];
    error_fd = error[0];
    // glibc 2.36's <sys/pidfd.h> declares pidfd_open without C linkage: the system call itself.
    pidfd = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
  }
  // A child never launched is killed; one that was ends by itself once its launcher reported.
  // Both are reaped here, before the memory group is removed.
  ~Parked() {
    if (!launched) ::kill(pid, SIGKILL);
    if (!reaped) wait_for(pid);
    ::close(command_fd);
    ::close(error_fd);
    if (pidfd >= 0) ::close(pidfd);
  }
  Parked(const Parked&) = delete;
  Parked& operator=(const Parked&) = delete;

  bool suits(Measurement measurement, std::uint64_t memory_bytes, const ProcessSpec& spec) const {
    return m == measurement && memory == memory_bytes && group_prefix == spec.group_name &&
           isolation == spec.isolation && sealed == (spec.seal == Seal::sealed) &&
           queries_directory == spec.queries_directory;
  }

  static bool fits(const ProcessSpec& spec) {
    std::size_t size =
        spec.executable.size() + spec.stdout_path.size() + spec.stderr_path.size() + 3;
    for (const auto& word : spec.argv) size += word.size() + 1;
    return size <= kLaunchBytes && spec.argv.size() + 4 <= kLaunchWords;
  }

  // Returns once the solver's process waits for its command (`solver` is its pid), or the child
  // has ended (a failed group join or fork: its error pipe says so). A sibling may hold the
  // child's end of the socket pair, so an ended child is noticed by polling for it, not by end of
  // file.
  void wait_ready() {
    pollfd ready{command_fd, POLLIN, 0};
    while (true) {
      if (::poll(&ready, 1, 10) > 0 && receive_ready()) return;
      siginfo_t info{};
      if (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOHANG | WNOWAIT) == 0 &&
          info.si_pid == pid)
        return;
    }
  }

  // The ready byte and, in its credentials, the solver's pid.
  bool receive_ready() {
    char byte = 0;
    iovec data{&byte, 1};
    alignas(cmsghdr) char control[CMSG_SPACE(sizeof(ucred))];
    msghdr message{};
    message.msg_iov = &data;
    message.msg_iovlen = 1;
    message.msg_control = control;
    message.msg_controllen = sizeof control;
    if (::recvmsg(command_fd, &message, MSG_DONTWAIT) != 1) return false;
    for (cmsghdr* c = CMSG_FIRSTHDR(&message); c != nullptr; c = CMSG_NXTHDR(&message, c))
      if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_CREDENTIALS) {
        ucred credentials{};
        std::memcpy(&credentials, CMSG_DATA(c), sizeof credentials);
        solver = credentials.pid;
      }
    return true;
  }

  // Waits for the launcher's report, sent once nothing of the query is left, or for the child's
  // end (a launcher that was killed sends none): the report when there is one. When the child
  // ended first it is reaped here, its resource use in `usage`.
  std::optional<LauncherReport> await_report(rusage& usage) {
    // The byte saying the solver's process executed comes first, when it was not read yet.
    char message[1 + sizeof(LauncherReport)];
    const std::size_t size = executed ? sizeof(LauncherReport) : sizeof message;
    const std::size_t have = await_bytes(message, size);
    if (have < size) {
      wait_for(pid, &usage);
      reaped = true;
      if (!read_exactly(command_fd, message + have, size - have, MSG_DONTWAIT)) return std::nullopt;
    }
    executed = true;
    LauncherReport r;
    std::memcpy(&r, message + (size - sizeof r), sizeof r);
    return r;
  }

  // Waits until the launcher says the solver's process has executed (or ended), or the child has
  // ended; without a pidfd, returns at once (the report then reads the byte).
  void await_exec() {
    char byte = 0;
    if (await_bytes(&byte, 1) == 1) executed = true;
  }

  // Reads `size` bytes from the launcher, or fewer when the child ends first (or cannot be
  // waited for: no pidfd): how many.
  std::size_t await_bytes(char* bytes, std::size_t size) {
    std::size_t have = 0;
    pollfd ends[2] = {{command_fd, POLLIN, 0}, {pidfd, POLLIN, 0}};
    while (pidfd >= 0 && have < size) {
      if (::poll(ends, 2, -1) < 0) {
        if (errno == EINTR) continue;
        break;
      }
      if (ends[0].revents != 0) {
        const ssize_t got = ::recv(command_fd, bytes + have, size - have, MSG_DONTWAIT);
        if (got > 0) have += static_cast<std::size_t>(got);
        // Every holder closed its end, or the socket failed: nothing more comes.
        if (got == 0 || (got < 0 && errno != EAGAIN && errno != EINTR)) ends[0].fd = -1;
      }
      if (ends[1].revents != 0 && have < size) break;
    }
    return have;
  }

  // Sends the command (fits(spec) holds), the executable's descriptor with its first bytes; a
  // child that has ended meanwhile is reaped as usual.
  void launch(const ProcessSpec& spec) {
    std::string text = spec.executable + '\0' + spec.stdout_path + '\0' + spec.stderr_path + '\0';
    for (const auto& word : spec.argv) text += word + '\0';
    LaunchHeader header;
    header.size = static_cast<std::uint32_t>(text.size());
    header.cpu = spec.cpu;
    header.rlimit_as = m == Measurement::rlimit_poll ? rlimit_backstop(memory) : 0;
    header.executable_fd = spec.executable_fd >= 0 ? 1 : 0;
    text.insert(0, reinterpret_cast<const char*>(&header), sizeof header);
    const int executable = spec.executable_fd;
    send_with_descriptors(command_fd, text.data(), text.size(), &executable,
                          executable >= 0 ? 1 : 0);
    launched = true;
  }
};

// The per-job watchdog thread: every 20 ms it checks the running solver against the stop flag,
// the deadline and (rlimit_poll) the query's resident memory, and kills the tree when one
// is passed; the job's thread meanwhile sits in a blocking wait4, so a solver's exit costs no more
// wake-ups than in a shell.
struct ProcessRunner::Watch {
  std::mutex mutex;
  std::condition_variable wake;
  bool quit = false, active = false;
  pid_t pid = -1;  // the solver's process, leader of its process group
  // The query's processes are the descendants of `root` from `first_level` down (query_usage).
  pid_t root = -1;
  int first_level = 1;
  Measurement m = Measurement::rlimit_poll;
  ProcessLimits limits;
  const std::vector<std::string>* files = nullptr;  // held to limits.output_bytes
  const MemoryGroup* group = nullptr;
  Clock::time_point deadline, kill_at;
  std::optional<Ending> reason;
  std::uint64_t peak = 0;
  std::thread thread;

  // Under the lock: what to do now for the active solver.
  void check(const std::atomic<bool>& stop, std::unique_lock<std::mutex>& lock) {
    if (!reason && (m == Measurement::rlimit_poll || limits.cpu_seconds > 0)) {
      const pid_t leader = pid, from = root;
      const int level = first_level;
      const bool with_cpu = limits.cpu_seconds > 0;
      lock.unlock();
      const QueryUsage usage = query_usage(from, level, with_cpu);
      lock.lock();
      if (!active || pid != leader) return;
      if (m == Measurement::rlimit_poll) {
        peak = std::max(peak, usage.rss_bytes);
        if (limits.memory_bytes != 0 && peak > limits.memory_bytes) reason = Ending::memory_limit;
      }
      if (!reason && limits.cpu_seconds > 0 && usage.cpu_seconds > limits.cpu_seconds)
        reason = Ending::cpu_limit;
    }
    if (!reason && files) {
      struct stat st {};
      for (const auto& file : *files)
        if (::stat(file.c_str(), &st) == 0 &&
            static_cast<std::uint64_t>(st.st_size) > limits.output_bytes)
          reason = Ending::output_limit;
    }
    const auto now = Clock::now();
    if (!reason && stop.load()) reason = Ending::interrupted;
    if (!reason && limits.wall_seconds > 0 && now >= deadline) reason = Ending::timeout;
    if (!reason) return;
    if (kill_at == Clock::time_point{}) {
      ::kill(-pid, SIGTERM);
      const double grace = *reason == Ending::memory_limit || *reason == Ending::output_limit
                               ? 0
                               : limits.grace_seconds;
      kill_at =
          now + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(grace));
    }
    if (now >= kill_at) {
      ::kill(-pid, SIGKILL);
      if (group) group->kill_all();
    }
  }

  void loop(const std::atomic<bool>& stop) {
    std::unique_lock lock(mutex);
    while (!quit) {
      wake.wait_for(lock, std::chrono::milliseconds(kPollMilliseconds));
      if (active) check(stop, lock);
    }
  }
};

// Destroys the children handed to it, oldest first, on its own thread (Parked's destructor reaps
// the child and removes its memory group).
struct ProcessRunner::Retirer {
  std::mutex mutex;
  std::condition_variable wake;
  std::deque<std::unique_ptr<Parked>> queue;
  bool quit = false;
  std::thread thread{[this] { loop(); }};

  ~Retirer() {
    {
      std::lock_guard lock(mutex);
      quit = true;
    }
    wake.notify_all();
    thread.join();
  }

  void add(std::unique_ptr<Parked> child) {
    {
      std::lock_guard lock(mutex);
      queue.push_back(std::move(child));
    }
    wake.notify_all();
  }

  // Runs until told to quit, and then until the queue is empty.
  void loop() {
    std::unique_lock lock(mutex);
    while (true) {
      wake.wait(lock, [this] { return quit || !queue.empty(); });
      if (queue.empty()) return;
      std::unique_ptr<Parked> child = std::move(queue.front());
      queue.pop_front();
      lock.unlock();
      child.reset();
      lock.lock();
    }
  }
};

ProcessRunner::ProcessRunner(const std::atomic<bool>& stop)
    : stop_(stop), watch_(std::make_unique<Watch>()), retirer_(std::make_unique<Retirer>()) {
  watch_->thread = std::thread([this] { watch_->loop(stop_); });
}

ProcessRunner::~ProcessRunner() {
  parked_.clear();
  retirer_.reset();
  if (network_fd_ >= 0) ::close(network_fd_);
  {
    std::lock_guard lock(watch_->mutex);
    watch_->quit = true;
  }
  watch_->wake.notify_all();
  watch_->thread.join();
}

namespace {

void classify_exit(int status, const MemoryGroup* g, ProcessOutcome& out);

// How the query ended, from what the watchdog saw (`reason`), the child's error pipe and the
// launcher's report; `out` holds the times already.
void outcome_of(const ProcessSpec& spec, int error_fd, const MemoryGroup* g,
                std::optional<Ending> reason, const std::optional<LauncherReport>& report,
                std::uint64_t peak, ProcessOutcome& out) {
  const auto failed_start = child_error(error_fd);
  if (failed_start && failed_start->stage == 3) {
    errno = failed_start->error;
    fail(spec.stdout_path + " or " + spec.stderr_path + ": cannot create");
  }
  const std::uint64_t solver_peak =
      report ? static_cast<std::uint64_t>(report->max_rss_kb) * 1024 : 0;
  out.peak_memory_bytes = g ? g->peak() : std::max(peak, solver_peak);
  if (report) out.left_descendants = report->leftovers != 0;
  if (failed_start) {
    static constexpr const char* kStages[] = {"",
                                              "cannot join the memory cgroup: ",
                                              "cannot run: ",
                                              "cannot open its output files: ",
                                              "cannot create a PID namespace: ",
                                              "cannot fork: ",
                                              "cannot seal the query: "};
    const int stage =
        failed_start->stage >= 1 && failed_start->stage <= 6 ? failed_start->stage : 2;
    out.ending = Ending::not_started;
    out.error = (stage == 2 ? spec.executable + ": " : std::string()) + kStages[stage] +
                errno_text(failed_start->error);
  } else if (reason) {
    out.ending = *reason;
  } else if (report) {
    classify_exit(report->status, g, out);
  } else {
    out.ending = Ending::not_started;
    out.error = "the solver's launcher ended without saying how the solver did";
  }
}

void classify_exit(int status, const MemoryGroup* g, ProcessOutcome& out) {
  if (WIFSIGNALED(status)) {
    out.ending = Ending::signaled;
    out.signal = WTERMSIG(status);
  } else {
    out.ending = Ending::exited;
    out.exit_code = WEXITSTATUS(status);
  }
  // A solver (or its child) the kernel's OOM killer hit, or one that failed after its group hit
  // the limit, ran out of memory.
  if (g &&
      (g->oom_killed() || ((out.ending != Ending::exited || out.exit_code != 0) && g->hit_limit())))
    out.ending = Ending::memory_limit;
}

}  // namespace

std::string seal_refusal() {
  SealSetup probe(true, "/", -1);
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) return errno_text(errno);
  const pid_t child = ::fork();
  if (child < 0) return errno_text(errno);
  if (child == 0) {
    const int error = seal_namespaces(probe) ? 0 : errno;
    (void)!::write(report[1], &error, sizeof error);
    ::_exit(0);
  }
  ::close(report[1]);
  int error = EIO;
  (void)!::read(report[0], &error, sizeof error);
  ::close(report[0]);
  wait_for(child);
  return error == 0 ? std::string() : errno_text(error);
}

ProcessOutcome ProcessRunner::run(const ProcessSpec& spec, const ProcessLimits& limits,
                                  Measurement m) {
  ProcessOutcome out;
  if (!parked_.empty() && !parked_.front()->suits(m, limits.memory_bytes, spec)) parked_.clear();
  if (parked_.empty())
    parked_.push_back(std::make_unique<Parked>(fork_server(), m, limits.memory_bytes, spec,
                                               sequence_++, network(spec)));
  std::unique_ptr<Parked> child = std::move(parked_.front());
  parked_.pop_front();
  if (!Parked::fits(spec)) {
    out.ending = Ending::not_started;
    out.error = spec.executable + ": cannot run: the command line is longer than " +
                std::to_string(kLaunchBytes) + " bytes";
    return out;
  }
  child->wait_ready();
  const auto started = Clock::now();
  const bool ready = child->solver > 0;  // else the child ended: its error pipe says why
  if (ready) {
    child->launch(spec);
    // Until it executes, the solver's process shares the launcher's memory (vfork): watched from
    // then on, its memory is its own.
    child->await_exec();
  }
  const MemoryGroup* g = child->group.get();
  if (ready) {
    std::lock_guard lock(watch_->mutex);
    Watch& w = *watch_;
    w.active = true;
    w.pid = child->solver;
    // The parked child is the launcher, or in a PID namespace the launcher's parent.
    w.root = child->pid;
    w.first_level = spec.isolation == Isolation::pid_namespace ? 2 : 1;
    w.m = m;
    w.limits = limits;
    w.files = &spec.watched_files;
    w.group = g;
    w.deadline = started + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(limits.wall_seconds));
    w.kill_at = {};
    w.reason.reset();
    w.peak = 0;
  }
  // The next queries' children join their groups while this solver runs: two ahead under
  // cgroup-v1, where a join waits for an RCU grace period, at times longer than a small query.
  // Should that fail, the next run() tries again and reports it; this solver is reaped first.
  const std::size_t ahead = m == Measurement::cgroup_v1 ? 2 : 1;
  try {
    while (!stop_.load() && parked_.size() < ahead)
      parked_.push_back(std::make_unique<Parked>(fork_server(), m, limits.memory_bytes, spec,
                                                 sequence_++, network(spec)));
  } catch (const Error&) {
  }
  if (ready && spec.while_running) spec.while_running();
  rusage usage{};
  const auto report = child->await_report(usage);
  // The launcher's clock says when the query ended: mosb may have read the report later (busy
  // with the previous query's record). Both clocks are CLOCK_MONOTONIC (libstdc++'s steady_clock);
  // a time outside [started, now] is not believed.
  const auto now = Clock::now();
  const auto ended = report
                         ? std::clamp(Clock::time_point(std::chrono::duration_cast<Clock::duration>(
                                          std::chrono::nanoseconds(report->sent_nanoseconds))),
                                      started, now)
                         : now;
  out.wall_seconds = std::chrono::duration<double>(ended - started).count();
  out.cpu_seconds = report ? static_cast<double>(report->cpu_microseconds) / 1e6
                           : seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime);
  std::optional<Ending> reason;
  std::uint64_t peak = 0;
  {
    std::lock_guard lock(watch_->mutex);
    watch_->active = false;
    watch_->files = nullptr;
    reason = watch_->reason;
    peak = watch_->peak;
  }
  if (ready) kill_leftovers(child->solver, out);
  outcome_of(spec, child->error_fd, g, reason, report, peak, out);
  retirer_->add(std::move(child));
  return out;
}

ForkServer& ProcessRunner::fork_server() {
  if (!fork_server_) fork_server_ = std::make_unique<ForkServer>();
  return *fork_server_;
}

int ProcessRunner::network(const ProcessSpec& spec) {
  // Per runner, not per query: making and tearing down a network namespace costs a query's worth
  // of milliseconds (BENCHMARKS.md), and the runner's queries run one after the other, each ended
  // with every process it had, so none can talk to another. Made on a thread of its own, since a
  // namespace is a thread's. Root only: an unprivileged query's network lives in its user
  // namespace, so it makes its own.
  if (spec.seal != Seal::sealed || ::geteuid() != 0 || network_fd_ >= 0) return network_fd_;
  std::thread([this] {
    if (::unshare(CLONE_NEWNET) == 0 && loopback_up())
      network_fd_ = ::open("/proc/thread-self/ns/net", O_RDONLY | O_CLOEXEC);
  }).join();
  return network_fd_;  // -1: each query makes its own, as unprivileged
}

namespace {

// Reads the two pipes of a program until both are closed, into its output.
void read_pipes(int out, int err, ProgramOutput& output) {
  pollfd fds[2] = {{out, POLLIN, 0}, {err, POLLIN, 0}};
  std::string* texts[2] = {&output.out, &output.err};
  int open = 2;
  char buffer[4096];
  while (open > 0) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = ::read(fds[i].fd, buffer, sizeof buffer);
      if (n > 0) {
        texts[i]->append(buffer, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        fds[i].fd = -1;
        --open;
      }
    }
  }
  for (auto& fd : fds)
    if (fd.fd >= 0) ::close(fd.fd);
}

}  // namespace

ProgramOutput run_program(const std::string& executable, const std::vector<std::string>& argv) {
  int out[2], err[2];
  if (::pipe2(out, O_CLOEXEC) != 0) fail("cannot create a pipe");
  if (::pipe2(err, O_CLOEXEC) != 0) {
    const int error = errno;
    ::close(out[0]);
    ::close(out[1]);
    errno = error;
    fail("cannot create a pipe");
  }
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_RDONLY);
    if (null >= 0) ::dup2(null, 0);
    execute(executable.c_str(), args.data(), out[1], err[1], -1);
  }
  in_parent_after_fork(pid, {out[1], err[1]}, {out[0], err[0]});
  ProgramOutput output;
  read_pipes(out[0], err[0], output);
  const int status = wait_for(pid);
  output.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return output;
}

}  // namespace run_internal

}  // namespace mosb
