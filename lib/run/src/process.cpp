#include "mosb/process.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <poll.h>
#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>

#include "mosb/error.hpp"

extern char** environ;

namespace mosb {

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

std::string read_small_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::optional<std::uint64_t> read_number(const std::string& path) {
  const std::string text = read_small_file(path);
  if (text.empty()) return std::nullopt;
  return std::strtoull(text.c_str(), nullptr, 10);
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

std::string_view to_string(Measurement m) {
  return m == Measurement::cgroup_v1 ? "cgroup-v1" : "rlimit-poll";
}

std::optional<Measurement> parse_measurement(std::string_view text) {
  if (text == "cgroup-v1") return Measurement::cgroup_v1;
  if (text == "rlimit-poll") return Measurement::rlimit_poll;
  return std::nullopt;
}

Measurement detect_measurement() {
  const std::string base = own_memory_cgroup();
  if (base.empty() || ::access((base + "/memory.limit_in_bytes").c_str(), W_OK) != 0)
    return Measurement::rlimit_poll;
  const std::string probe = base + "/mosb-probe-" + std::to_string(::getpid());
  if (::mkdir(probe.c_str(), 0700) != 0) return Measurement::rlimit_poll;
  ::rmdir(probe.c_str());
  return Measurement::cgroup_v1;
}

std::string describe_measurement(Measurement m) {
  const std::string time =
      "wall: steady clock from exec to reaping; cpu: user+system of the solver and every "
      "descendant reaped (wait4)";
  if (m == Measurement::cgroup_v1)
    return time +
           "; memory: cgroup v1 memory controller, one group per query (memory.limit_in_bytes "
           "and memory.memsw.limit_in_bytes limit, memory.max_usage_in_bytes is the peak, "
           "page cache included; an OOM kill in the group is memory-limit)";
  return time +
         "; memory: RLIMIT_AS per process, and the resident set summed over the solver's "
         "session polled every 20 ms (peak = largest sum; a sum over the limit is memory-limit)";
}

std::string resolve_executable(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return {};
}

void prepare_process_runner() {
  ::prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0);
}

namespace {

// The resident memory, in bytes, of every process in session `sid`.
std::uint64_t session_rss(pid_t sid) {
  static const long page = ::sysconf(_SC_PAGESIZE);
  std::uint64_t total = 0;
  DIR* proc = ::opendir("/proc");
  if (!proc) return 0;
  while (const dirent* entry = ::readdir(proc)) {
    if (entry->d_name[0] < '0' || entry->d_name[0] > '9') continue;
    const std::string text = read_small_file(std::string("/proc/") + entry->d_name + "/stat");
    const auto close = text.rfind(')');
    if (close == std::string::npos) continue;
    // After "pid (comm)": state ppid pgrp session ... field 24 is rss (in pages).
    std::stringstream fields(text.substr(close + 2));
    std::string field;
    long session = -1;
    long rss = 0;
    for (int i = 3; i <= 24 && fields >> field; ++i) {
      if (i == 6) session = std::atol(field.c_str());
      if (i == 24) rss = std::atol(field.c_str());
    }
    if (session == sid && rss > 0) total += static_cast<std::uint64_t>(rss) * page;
  }
  ::closedir(proc);
  return total;
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
  }
  ~MemoryGroup() {
    kill_all();
    for (int i = 0; i < 200 && ::rmdir(dir_.c_str()) != 0 && errno == EBUSY; ++i) {
      kill_all();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  MemoryGroup(const MemoryGroup&) = delete;
  MemoryGroup& operator=(const MemoryGroup&) = delete;

  void add(pid_t pid) const {
    if (!write_file(dir_ + "/cgroup.procs", std::to_string(pid)))
      fail(dir_ + "/cgroup.procs: cannot move the solver into its group");
  }
  void kill_all() const {
    for (const pid_t pid : cgroup_members(dir_)) ::kill(pid, SIGKILL);
  }
  bool empty() const { return cgroup_members(dir_).empty(); }
  std::optional<std::uint64_t> peak() const {
    return read_number(dir_ + "/memory.max_usage_in_bytes");
  }
  bool oom_killed() const {
    const std::string oom = read_small_file(dir_ + "/memory.oom_control");
    return keyed_value(oom, "oom_kill") > 0 || keyed_value(oom, "under_oom") > 0;
  }
  bool hit_limit() const { return read_number(dir_ + "/memory.failcnt").value_or(0) > 0; }

 private:
  std::string dir_;
};

struct Pipes {
  int sync[2] = {-1, -1};   // parent -> child: "you are in your group, exec"
  int error[2] = {-1, -1};  // child -> parent: errno of a failed exec (EOF on success)
  ~Pipes() {
    for (int fd : {sync[0], sync[1], error[0], error[1]})
      if (fd >= 0) ::close(fd);
  }
};

// After fork, in the child: only async-signal-safe calls.
[[noreturn]] void start_child(const ProcessSpec& spec, const std::vector<char*>& argv, int out,
                              int err, int in, const Pipes& pipes, std::uint64_t rlimit_as) {
  ::setsid();
  // A kill -9 of mosb run takes the solver with it (its descendants are left to their session).
  ::prctl(PR_SET_PDEATHSIG, SIGKILL, 0, 0, 0);
  sigset_t none;
  sigemptyset(&none);
  ::sigprocmask(SIG_SETMASK, &none, nullptr);
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
  ::signal(SIGPIPE, SIG_DFL);
  if (spec.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(spec.cpu, &set);
    ::sched_setaffinity(0, sizeof set, &set);
  }
  if (rlimit_as != 0) {
    const rlimit limit{rlimit_as, rlimit_as};
    ::setrlimit(RLIMIT_AS, &limit);
  }
  ::dup2(in, 0);
  ::dup2(out, 1);
  ::dup2(err, 2);
  // A byte, not EOF: a sibling forked by another job's thread holds copies of this pipe's ends
  // until it executes, so EOF could wait on it.
  char go = 0;
  while (::read(pipes.sync[0], &go, 1) < 0 && errno == EINTR) {
  }
  if (go != 1) ::_exit(127);
  ::execve(spec.executable.c_str(), argv.data(), environ);
  const int error = errno;
  (void)!::write(pipes.error[1], &error, sizeof error);
  ::_exit(127);
}

int open_output(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) fail(path + ": cannot create");
  return fd;
}

}  // namespace

namespace {

double seconds_of(const timeval& t) {
  return static_cast<double>(t.tv_sec) + t.tv_usec / 1e6;
}

// Waits for the solver's own process; what it costs is added to `out`.
class Waiter {
 public:
  explicit Waiter(pid_t pid) : pid_(pid) {
    pidfd_ = static_cast<int>(::syscall(SYS_pidfd_open, pid, 0));
  }
  ~Waiter() {
    if (pidfd_ >= 0) ::close(pidfd_);
  }
  Waiter(const Waiter&) = delete;
  Waiter& operator=(const Waiter&) = delete;

  // Waits up to `ms` milliseconds; true once the solver has been reaped (status in status()).
  bool wait(int ms, ProcessOutcome& out) {
    if (reaped_) return true;
    if (pidfd_ >= 0) {
      pollfd p{pidfd_, POLLIN, 0};
      ::poll(&p, 1, ms);
    }
    rusage usage{};
    const pid_t r = ::wait4(pid_, &status_, WNOHANG, &usage);
    if (r == pid_) {
      reaped_ = true;
      max_rss_ = static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
      out.cpu_seconds += seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime);
      return true;
    }
    if (pidfd_ < 0) std::this_thread::sleep_for(std::chrono::milliseconds(ms));
    return false;
  }
  int status() const { return status_; }
  // The largest resident set of the solver or a descendant it reaped (not their sum).
  std::uint64_t max_rss() const { return max_rss_; }

 private:
  pid_t pid_;
  int pidfd_ = -1;
  int status_ = 0;
  bool reaped_ = false;
  std::uint64_t max_rss_ = 0;
};

// Kills everything left of the solver's session and reaps what became ours (subreaper).
void kill_leftovers(pid_t sid, const MemoryGroup* group, ProcessOutcome& out) {
  const auto until = Clock::now() + std::chrono::seconds(5);
  while (true) {
    ::kill(-sid, SIGKILL);
    if (group) group->kill_all();
    int status = 0;
    rusage usage{};
    while (::wait4(-sid, &status, WNOHANG, &usage) > 0)
      out.cpu_seconds += seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime);
    if (::kill(-sid, 0) != 0 && errno == ESRCH && (!group || group->empty())) return;
    if (Clock::now() > until) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

}  // namespace

namespace {

// RLIMIT_AS under rlimit_poll: twice the limit, a backstop for allocations faster than the poll.
// The address space of a process exceeds its resident memory (libraries, reserved arenas), so the
// limit itself would refuse solvers well below it; the poll enforces the limit on resident memory.
std::uint64_t rlimit_backstop(std::uint64_t memory) {
  return memory == 0 ? 0 : memory > (UINT64_MAX / 2) ? memory : memory * 2;
}

// Starts the solver; returns its pid, or -1 with out.error set when the exec failed.
pid_t start(const ProcessSpec& spec, Measurement m, std::uint64_t memory, const MemoryGroup* group,
            ProcessOutcome& out) {
  std::vector<char*> argv;
  for (const auto& word : spec.argv) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  const int out_fd = open_output(spec.stdout_path), err_fd = open_output(spec.stderr_path);
  const int in_fd = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
  Pipes pipes;
  if (::pipe2(pipes.sync, O_CLOEXEC) != 0 || ::pipe2(pipes.error, O_CLOEXEC) != 0)
    fail("cannot create a pipe");
  const pid_t pid = ::fork();
  if (pid == 0)
    start_child(spec, argv, out_fd, err_fd, in_fd, pipes,
                m == Measurement::rlimit_poll ? rlimit_backstop(memory) : 0);
  const int fork_error = errno;
  for (int fd : {out_fd, err_fd, in_fd}) ::close(fd);
  if (pid < 0) {
    errno = fork_error;
    fail("cannot fork");
  }
  ::close(pipes.sync[0]);
  pipes.sync[0] = -1;
  ::close(pipes.error[1]);
  pipes.error[1] = -1;
  if (group) group->add(pid);
  const char go = 1;
  if (::write(pipes.sync[1], &go, 1) != 1) fail("cannot start the solver");
  int error = 0;
  ssize_t got = 0;
  while ((got = ::read(pipes.error[0], &error, sizeof error)) < 0 && errno == EINTR) {
  }
  if (got == sizeof error) {
    ::waitpid(pid, nullptr, 0);
    out.ending = Ending::not_started;
    out.error = spec.executable + ": cannot run: " + errno_text(error);
    return -1;
  }
  return pid;
}

// SIGTERM to the tree, up to `grace` for the solver to end, then SIGKILL.
void terminate(pid_t pid, double grace, const MemoryGroup* group, Waiter& waiter,
               ProcessOutcome& out) {
  ::kill(-pid, SIGTERM);
  const auto until = Clock::now() + std::chrono::duration<double>(grace);
  while (Clock::now() < until)
    if (waiter.wait(kPollMilliseconds, out)) break;
  ::kill(-pid, SIGKILL);
  if (group) group->kill_all();
  while (!waiter.wait(kPollMilliseconds, out)) {
  }
}

}  // namespace

ProcessOutcome run_process(const ProcessSpec& spec, const ProcessLimits& limits, Measurement m,
                           const std::atomic<bool>& stop) {
  ProcessOutcome out;
  std::optional<MemoryGroup> group;
  if (m == Measurement::cgroup_v1) group.emplace(spec.group_name, limits.memory_bytes);
  const MemoryGroup* g = group ? &*group : nullptr;
  const auto started = Clock::now();
  const pid_t pid = start(spec, m, limits.memory_bytes, g, out);
  if (pid < 0) return out;
  Waiter waiter(pid);
  const auto deadline = started + std::chrono::duration<double>(limits.wall_seconds);
  std::uint64_t peak = 0;
  bool killed = false;
  while (!waiter.wait(kPollMilliseconds, out)) {
    std::optional<Ending> reason;
    if (stop.load()) reason = Ending::interrupted;
    if (limits.wall_seconds > 0 && Clock::now() >= deadline) reason = Ending::timeout;
    if (m == Measurement::rlimit_poll) {
      peak = std::max(peak, session_rss(pid));
      if (limits.memory_bytes != 0 && peak > limits.memory_bytes) reason = Ending::memory_limit;
    }
    if (reason) {
      out.ending = *reason;
      terminate(pid, *reason == Ending::memory_limit ? 0 : limits.grace_seconds, g, waiter, out);
      killed = true;
      break;
    }
  }
  out.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  kill_leftovers(pid, g, out);
  if (g) {
    out.peak_memory_bytes = g->peak();
    if (!killed && g->oom_killed()) out.ending = Ending::memory_limit, killed = true;
  } else {
    out.peak_memory_bytes = std::max(peak, waiter.max_rss());
  }
  if (killed) return out;
  const int status = waiter.status();
  if (WIFSIGNALED(status)) {
    out.ending = Ending::signaled;
    out.signal = WTERMSIG(status);
  } else {
    out.ending = Ending::exited;
    out.exit_code = WEXITSTATUS(status);
  }
  if (g && out.ending != Ending::exited && g->hit_limit()) out.ending = Ending::memory_limit;
  if (g && out.ending == Ending::exited && out.exit_code != 0 && g->hit_limit())
    out.ending = Ending::memory_limit;
  return out;
}

}  // namespace mosb
