// Starting programs, the one place lib/run forks and executes: one solver process tree of `mosb
// run`, limited and measured (spec/RUN.md §4), and the short programs a SLURM run asks (sbatch,
// squeue, sacct), their output captured. The solver starts in a process group of its own
// (setpgid), which holds the whole tree unless a descendant leaves it; the tree is killed by group
// (and, under a cgroup, by the cgroup's member list), on a limit, on an interrupt and after the
// solver exits, so nothing it started outlives it.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "mosb/enum_names.hpp"
#include "mosb/run.hpp"

namespace mosb::run_internal {

// The best mechanism this process can use: cgroup_v1 when a child group can be created in its
// memory cgroup, else rlimit_poll.
Measurement detect_measurement();
// One sentence per figure saying how it is measured under `m` (for the run's metadata).
std::string describe_measurement(Measurement m);

// How the processes of one query are held together, so that none outlives the query
// (spec/RUN.md §4): chosen once per run.
enum class Isolation {
  // The solver runs in a PID namespace of its own under a small init: when the solver ends, the
  // init kills everything left in the namespace, and a kill of the init (or of mosb run) ends the
  // namespace. Nothing can leave a PID namespace. Needs CAP_SYS_ADMIN (root).
  pid_namespace,
  // The solver's launcher is a child subreaper: a descendant that leaves the process group or
  // the session is still reparented to it, and killed when the solver ends.
  subreaper,
};
inline constexpr auto kIsolationNames = enum_names<Isolation>({
    {Isolation::pid_namespace, "pid-namespace"},
    {Isolation::subreaper, "subreaper"},
});
// pid_namespace when this process may create one, else subreaper.
Isolation detect_isolation();

// Whether this process can seal a query: an empty text when it can, else the kernel's refusal.
std::string seal_refusal();

struct ProcessSpec {
  std::string executable;  // resolved path (resolve_executable)
  // >= 0: the executable opened once for the whole run, executed through this descriptor
  // (fexecve), so every query runs that very file whatever happens to its path meanwhile.
  int executable_fd = -1;
  std::vector<std::string> argv;  // argv[0] as the template gave it
  // Created by the solver's process, exclusively: a path is never reused for another query.
  std::string stdout_path, stderr_path;
  // Files whose size the watchdog holds to `ProcessLimits::output_bytes` (stdout, stderr, the
  // {front} file): a tree that writes more is killed (Ending::output_limit).
  std::vector<std::string> watched_files;
  int cpu = -1;            // >= 0: pin the tree to this CPU (sched_setaffinity)
  std::string group_name;  // unique per concurrent process: the cgroup's name
  Isolation isolation = Isolation::subreaper;
  Seal seal = Seal::none;
  // With a seal: the directory holding every query directory of this runner (the directory of
  // stdout_path is a subdirectory of it, the one the solver may write).
  std::string queries_directory;
  // mosb's own work that need not wait for the solver (the previous query's cleanup): called once
  // on the calling thread while the solver runs, off the path from one query to the next. Must
  // not throw.
  std::function<void()> while_running;
};

enum class Ending {
  exited,        // exit_code holds the status
  signaled,      // signal holds the signal
  timeout,       // killed at the wall-clock limit
  cpu_limit,     // killed at the CPU-time limit
  memory_limit,  // killed (or failed) at the memory limit
  output_limit,  // killed when a watched file passed ProcessLimits::output_bytes
  interrupted,   // killed because `stop` was set
  not_started,   // the executable could not be run: error says why
};

struct ProcessOutcome {
  Ending ending = Ending::exited;
  int exit_code = 0, signal = 0;
  double wall_seconds = 0;  // from the command to the launcher's report (spec/RUN.md §4)
  double cpu_seconds = 0;   // user + system of the solver and its reaped descendants
  std::optional<std::uint64_t> peak_memory_bytes;
  std::string error;
  // Descendants still alive when the solver ended, killed then (they left its process group or
  // lived on after it): counted, so the run can say so.
  bool left_descendants = false;
};

// Must be called once before ProcessRunner::run, from the main thread before other threads start:
// makes this process the reaper of orphaned descendants (PR_SET_CHILD_SUBREAPER), a backstop: each
// query's launcher kills what its solver left (Isolation), and a launcher that was killed leaves
// its orphans here, never to init.
void prepare_process_runner();

class ForkServer;

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
  // The next queries' solver processes, forked ahead of their commands, oldest first.
  std::deque<std::unique_ptr<Parked>> parked_;
  // Children whose query has ended, reaped and their memory groups removed by a thread of their
  // own: a query ends on its launcher's report, not on the exits that follow it, and removing a
  // v1 memory group takes the kernel most of a millisecond, which the job's thread would
  // otherwise spend while the next solver's report waits.
  struct Retirer;
  std::unique_ptr<Retirer> retirer_;
  // The fork server of this runner's children, started on first use (from the runner's thread).
  std::unique_ptr<ForkServer> fork_server_;
  ForkServer& fork_server();
  // The network namespace the sealed queries of this runner share (root), made on first use.
  int network(const ProcessSpec& spec);
  int network_fd_ = -1;
  std::uint64_t sequence_ = 0;  // numbers the memory groups of this runner
};

// What a program run to its end printed, and how it ended.
struct ProgramOutput {
  int status = -1;  // exit status, or -1 when killed by a signal
  std::string out, err;
};

// Runs `executable` (a resolved path) with `argv` (argv[0] as given) and no shell, its standard
// input /dev/null, and waits for it; throws mosb::Error (io) when it cannot be started.
ProgramOutput run_program(const std::string& executable, const std::vector<std::string>& argv);

}  // namespace mosb::run_internal
