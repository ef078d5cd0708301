#include "mosb/process.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sched.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <sstream>
#include <thread>

#include "mosb/error.hpp"

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
    std::string candidate = (dir.empty() ? "." : dir) + "/" + name;
    struct stat st {};
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) &&
        ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
  }
  return {};
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
    procs_ = ::open((dir_ + "/cgroup.procs").c_str(), O_WRONLY | O_CLOEXEC);
    if (procs_ < 0) fail(dir_ + "/cgroup.procs: cannot open");
  }
  ~MemoryGroup() {
    ::close(procs_);
    kill_all();
    for (int i = 0; i < 200 && ::rmdir(dir_.c_str()) != 0 && errno == EBUSY; ++i) {
      kill_all();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  MemoryGroup(const MemoryGroup&) = delete;
  MemoryGroup& operator=(const MemoryGroup&) = delete;

  // The child writes "0" here (itself) before it executes: no round trip through the parent.
  int procs_fd() const { return procs_; }
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
  int procs_ = -1;
};

// What the child reports through its error pipe when it cannot execute.
struct ChildError {
  int stage = 0;  // 1: joining the cgroup, 2: execve
  int error = 0;
};

// After fork, in the child: only async-signal-safe calls.
[[noreturn]] void start_child(const ProcessSpec& spec, const std::vector<char*>& argv,
                              const int fds[3], int procs_fd, int error_fd,
                              std::uint64_t rlimit_as) {
  ChildError report;
  if (procs_fd >= 0 && ::write(procs_fd, "0", 1) != 1) {
    report = {1, errno};
    (void)!::write(error_fd, &report, sizeof report);
    ::_exit(127);
  }
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
  for (int i = 0; i < 3; ++i) ::dup2(fds[i], i);
  ::execve(spec.executable.c_str(), argv.data(), environ);
  report = {2, errno};
  (void)!::write(error_fd, &report, sizeof report);
  ::_exit(127);
}

int open_output(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) fail(path + ": cannot create");
  return fd;
}

double seconds_of(const timeval& t) {
  return static_cast<double>(t.tv_sec) + t.tv_usec / 1e6;
}

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

// RLIMIT_AS under rlimit_poll: twice the limit, a backstop for allocations faster than the poll.
// The address space of a process exceeds its resident memory (libraries, reserved arenas), so the
// limit itself would refuse solvers well below it; the poll enforces the limit on resident memory.
std::uint64_t rlimit_backstop(std::uint64_t memory) {
  return memory == 0 ? 0 : memory > (UINT64_MAX / 2) ? memory : memory * 2;
}

struct Spawned {
  pid_t pid = -1;
  int error_fd = -1;  // read end of the child's error pipe
};

// Forks the solver; it joins its group and executes by itself, so the parent never waits for it.
Spawned spawn(const ProcessSpec& spec, Measurement m, std::uint64_t memory,
              const MemoryGroup* group) {
  std::vector<char*> argv;
  for (const auto& word : spec.argv) argv.push_back(const_cast<char*>(word.c_str()));
  argv.push_back(nullptr);
  const int fds[3] = {::open("/dev/null", O_RDONLY | O_CLOEXEC), open_output(spec.stdout_path),
                      open_output(spec.stderr_path)};
  int error_pipe[2];
  // Non-blocking: read after the child ended, when a sibling forked meanwhile may still hold the
  // write end (until it executes).
  if (::pipe2(error_pipe, O_CLOEXEC) != 0) fail("cannot create a pipe");
  ::fcntl(error_pipe[0], F_SETFL, O_NONBLOCK);
  const pid_t pid = ::fork();
  if (pid == 0)
    start_child(spec, argv, fds, group ? group->procs_fd() : -1, error_pipe[1],
                m == Measurement::rlimit_poll ? rlimit_backstop(memory) : 0);
  const int fork_error = errno;
  for (int fd : fds) ::close(fd);
  ::close(error_pipe[1]);
  if (pid < 0) {
    ::close(error_pipe[0]);
    errno = fork_error;
    fail("cannot fork");
  }
  return {pid, error_pipe[0]};
}

// The child's report of a failed start, read once it has ended (nothing: it executed).
std::optional<ChildError> child_error(int fd) {
  ChildError report;
  const ssize_t got = ::read(fd, &report, sizeof report);
  ::close(fd);
  if (got != sizeof report) return std::nullopt;
  return report;
}

}  // namespace

// The per-job watchdog thread: every 20 ms it checks the running solver against the stop flag,
// the deadline and (rlimit_poll) the session's resident memory, and kills the tree when one is
// passed; the job's thread meanwhile sits in a blocking wait4, so a solver's exit costs no more
// wake-ups than in a shell.
struct ProcessRunner::Watch {
  std::mutex mutex;
  std::condition_variable wake;
  bool quit = false, active = false;
  pid_t pid = -1;
  Measurement m = Measurement::rlimit_poll;
  ProcessLimits limits;
  const MemoryGroup* group = nullptr;
  Clock::time_point deadline, kill_at;
  std::optional<Ending> reason;
  std::uint64_t peak = 0;
  std::thread thread;

  // Under the lock: what to do now for the active solver.
  void check(const std::atomic<bool>& stop, std::unique_lock<std::mutex>& lock) {
    if (!reason && m == Measurement::rlimit_poll) {
      const pid_t sid = pid;
      lock.unlock();
      const std::uint64_t rss = session_rss(sid);
      lock.lock();
      if (!active || pid != sid) return;
      peak = std::max(peak, rss);
      if (limits.memory_bytes != 0 && peak > limits.memory_bytes) reason = Ending::memory_limit;
    }
    const auto now = Clock::now();
    if (!reason && stop.load()) reason = Ending::interrupted;
    if (!reason && limits.wall_seconds > 0 && now >= deadline) reason = Ending::timeout;
    if (!reason) return;
    if (kill_at == Clock::time_point{}) {
      ::kill(-pid, SIGTERM);
      const double grace = *reason == Ending::memory_limit ? 0 : limits.grace_seconds;
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

ProcessRunner::ProcessRunner(const std::atomic<bool>& stop)
    : stop_(stop), watch_(std::make_unique<Watch>()) {
  watch_->thread = std::thread([this] { watch_->loop(stop_); });
}

ProcessRunner::~ProcessRunner() {
  {
    std::lock_guard lock(watch_->mutex);
    watch_->quit = true;
  }
  watch_->wake.notify_all();
  watch_->thread.join();
}

namespace {

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

ProcessOutcome ProcessRunner::run(const ProcessSpec& spec, const ProcessLimits& limits,
                                  Measurement m) {
  ProcessOutcome out;
  std::optional<MemoryGroup> group;
  if (m == Measurement::cgroup_v1) group.emplace(spec.group_name, limits.memory_bytes);
  const MemoryGroup* g = group ? &*group : nullptr;
  const auto started = Clock::now();
  const Spawned child = spawn(spec, m, limits.memory_bytes, g);
  {
    std::lock_guard lock(watch_->mutex);
    Watch& w = *watch_;
    w.active = true;
    w.pid = child.pid;
    w.m = m;
    w.limits = limits;
    w.group = g;
    w.deadline = started + std::chrono::duration_cast<Clock::duration>(
                               std::chrono::duration<double>(limits.wall_seconds));
    w.kill_at = {};
    w.reason.reset();
    w.peak = 0;
  }
  int status = 0;
  rusage usage{};
  while (::wait4(child.pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  out.wall_seconds = std::chrono::duration<double>(Clock::now() - started).count();
  out.cpu_seconds = seconds_of(usage.ru_utime) + seconds_of(usage.ru_stime);
  std::optional<Ending> reason;
  std::uint64_t peak = 0;
  {
    std::lock_guard lock(watch_->mutex);
    watch_->active = false;
    reason = watch_->reason;
    peak = watch_->peak;
  }
  kill_leftovers(child.pid, g, out);
  const auto failed_start = child_error(child.error_fd);
  out.peak_memory_bytes =
      g ? g->peak() : std::max(peak, static_cast<std::uint64_t>(usage.ru_maxrss) * 1024);
  if (failed_start) {
    out.ending = Ending::not_started;
    out.error = (failed_start->stage == 1 ? "cannot join the memory cgroup: "
                                          : spec.executable + ": cannot run: ") +
                errno_text(failed_start->error);
  } else if (reason) {
    out.ending = *reason;
  } else {
    classify_exit(status, g, out);
  }
  return out;
}

}  // namespace mosb
