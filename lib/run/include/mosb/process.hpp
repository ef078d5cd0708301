// One solver process tree of `mosb run`, limited and measured (spec/RUN.md §4). The solver starts
// in a process group of its own (setpgid), which holds the whole tree unless a descendant leaves
// it; the tree is killed by group (and, under a cgroup, by the cgroup's member list), on a
// limit, on an interrupt and after the solver exits, so nothing it started outlives it.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mosb {

// How memory is limited and measured; time is measured the same way by all.
enum class Measurement {
  // A memory cgroup (v1 controller) per query: memory.limit_in_bytes (and memsw when present)
  // limits the tree, memory.max_usage_in_bytes is its peak, an OOM kill in the group (or failcnt
  // with a failing solver) is a memory-limit.
  cgroup_v1,
  // RLIMIT_AS per process plus the tree's resident set (/proc/PID/stat of every process of the
  // solver's process group) polled every 20 ms: its largest sum is the peak, a sum over the limit
  // kills.
  rlimit_poll,
};
std::string_view to_string(Measurement m);  // "cgroup-v1", "rlimit-poll"
std::optional<Measurement> parse_measurement(std::string_view text);
// The best mechanism this process can use: cgroup_v1 when a child group can be created in its
// memory cgroup, else rlimit_poll.
Measurement detect_measurement();
// One sentence per figure saying how it is measured under `m` (for the run's metadata).
std::string describe_measurement(Measurement m);

struct ProcessLimits {
  double wall_seconds = 0;         // 0: none
  std::uint64_t memory_bytes = 0;  // 0: none (still measured)
  double grace_seconds = 1;        // between SIGTERM and SIGKILL on a timeout
  // 0: none. User + system time of the solver's process group (its live processes and the children
  // they reaped), polled every 20 ms.
  double cpu_seconds = 0;
};

struct ProcessSpec {
  std::string executable;         // resolved path (resolve_executable)
  std::vector<std::string> argv;  // argv[0] as the template gave it
  std::string stdout_path, stderr_path;
  int cpu = -1;            // >= 0: pin the tree to this CPU (sched_setaffinity)
  std::string group_name;  // unique per concurrent process: the cgroup's name
};

enum class Ending {
  exited,        // exit_code holds the status
  signaled,      // signal holds the signal
  timeout,       // killed at the wall-clock limit
  cpu_limit,     // killed at the CPU-time limit
  memory_limit,  // killed (or failed) at the memory limit
  interrupted,   // killed because `stop` was set
  not_started,   // the executable could not be run: error says why
};

struct ProcessOutcome {
  Ending ending = Ending::exited;
  int exit_code = 0, signal = 0;
  double wall_seconds = 0;  // from the exec to the reaping of the solver
  double cpu_seconds = 0;   // user + system of the solver and its reaped descendants
  std::optional<std::uint64_t> peak_memory_bytes;
  std::string error;
};

// The executable `name` names: a name with '/' as it is, else the first executable file of that
// name in $PATH (empty when none).
std::string resolve_executable(const std::string& name);

// Must be called once before ProcessRunner::run, from the main thread before other threads start:
// makes this process the reaper of orphaned descendants (PR_SET_CHILD_SUBREAPER), so a solver's
// children that outlive it are killed and reaped here, never left to init.
void prepare_process_runner();

// Runs solvers one after the other (one per job of `mosb run`), each to its end under its
// limits. A watchdog thread of its own checks the running solver every 20 ms against `stop`, the
// deadline, the CPU-time limit and, under rlimit_poll, the memory limit.
class ProcessRunner {
 public:
  explicit ProcessRunner(const std::atomic<bool>& stop);
  ~ProcessRunner();
  ProcessRunner(const ProcessRunner&) = delete;
  ProcessRunner& operator=(const ProcessRunner&) = delete;

  // Throws mosb::Error only when mosb itself cannot set up (files, cgroup, fork).
  ProcessOutcome run(const ProcessSpec& spec, const ProcessLimits& limits, Measurement m);

 private:
  struct Watch;
  struct Parked;
  const std::atomic<bool>& stop_;
  std::unique_ptr<Watch> watch_;
  std::unique_ptr<Parked> parked_;  // the next solver's process, forked ahead of its command
  std::uint64_t sequence_ = 0;      // numbers the memory groups of this runner
};

}  // namespace mosb
