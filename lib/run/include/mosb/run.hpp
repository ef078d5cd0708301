// `mosb run` (spec/RUN.md): one solver process per query of a query set, each limited and measured
// (spec/RUN.md §4), its output read by an adapter (the solver protocol by default), every finished
// query appended to a journal beside the output, and at the end one solution file written
// atomically through SolutionWriter. Queries are indexed 0..Q-1 in the query set's order; the
// journal holds one record per query, so a run may be resumed, or split into shards (run only the
// queries of shard i of N; the other queries stay not-run, and `solutions merge` joins the shards).
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/enum_names.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/query.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_merge.hpp"
#include "mosb/solver_protocol.hpp"
#include "mosb/views.hpp"

namespace mosb {

// How memory is limited and measured; time is measured the same way by all.
enum class Measurement {
  // A memory cgroup (v1 controller) per query: memory.limit_in_bytes (and memsw when present)
  // limits the tree, memory.max_usage_in_bytes is its peak, an OOM kill in the group (or failcnt
  // with a failing solver) is a memory-limit.
  cgroup_v1,
  // The resident set of the query's processes polled every 20 ms: /proc/PID/statm of every
  // descendant of the query's launcher, not the launcher itself (found through
  // /proc/PID/task/TID/children, so a process that left the solver's process group or session
  // still counts); the largest sum is the peak, a sum over the limit kills. RLIMIT_AS of twice
  // the limit on every process is a backstop for allocations faster than the poll (RUN.md §4).
  rlimit_poll,
};
inline constexpr auto kMeasurementNames = enum_names<Measurement>({
    {Measurement::cgroup_v1, "cgroup-v1"},
    {Measurement::rlimit_poll, "rlimit-poll"},
});
std::string_view to_string(Measurement m);  // kMeasurementNames
std::optional<Measurement> parse_measurement(std::string_view text);

// What a query's processes may reach of the filesystem and the network (spec/RUN.md §4.1).
enum class Seal {
  // A mount namespace of their own (root's; otherwise in a user namespace that maps the user
  // alone): every mount read-only but the query's own directory, a private tmpfs on /dev/shm,
  // a read-only /proc of their PID namespace (root), a network namespace with loopback alone,
  // and no capabilities. The instance, the export cache, the journal, the results, other queries
  // and other runs stay readable, and no solver can write them.
  sealed,
  // The user's filesystem and network as they are.
  none,
};
inline constexpr auto kSealNames = enum_names<Seal>({
    {Seal::sealed, "seal"},
    {Seal::none, "none"},
});

inline constexpr std::uint64_t kDefaultOutputBytes = std::uint64_t{1} << 30;  // 1 GiB

struct ProcessLimits {
  double wall_seconds = 0;         // 0: none
  std::uint64_t memory_bytes = 0;  // 0: none (still measured)
  double grace_seconds = 1;        // between SIGTERM and SIGKILL on a timeout
  // 0: none. User + system time of the query's processes (the launcher's descendants, found as
  // for rlimit_poll), each with the children it has reaped (/proc/PID/stat), polled every 20 ms.
  double cpu_seconds = 0;
  // The most bytes a solver may write to any one output file (stdout, stderr, {front}), and the
  // most a compressed log may decompress to; a front of more than output_bytes / 8 values is
  // refused too. What mosb holds of a query's output stays within it (spec/RUN.md §4).
  std::uint64_t output_bytes = kDefaultOutputBytes;
};

// "60", "60s", "1.5m", "2h", "500ms": seconds (the limits' text of `mosb run` and of an
// experiment file), decimal only; nullopt when malformed, negative or above 1e9 s.
std::optional<double> parse_duration(std::string_view text);
// "4294967296", "100B", "512M", "16g", "1T" (K, M, G, T in either case: powers of 1024; an
// optional "B" or "iB" after the multiplier, "B" alone for bytes): bytes; nullopt when malformed
// or above 2^64 - 1. The one size grammar: every size option and an experiment file's sizes.
std::optional<std::uint64_t> parse_memory_size(std::string_view text);

// "CPU MODEL, N cores, memory M kB, Linux RELEASE ARCH" from /proc and uname.
std::string describe_machine();

// What one solver process left behind for one query.
struct SolverOutputFiles {
  std::string stdout_path, stderr_path;
  std::string front_path;  // the {front} file (read instead of stdout when front_in_file)
  std::string fronts_dir;  // the {fronts} directory (example-log)
  bool front_in_file = false;
  Query query;
  std::size_t objectives = 0;
  // Which objectives take integers (an integer value must be written as one, at most 2^53, and is
  // read exactly); empty: none.
  std::vector<bool> integer_objectives;
  // What an adapter may hold: at most this many bytes of any one file (a decompressed log
  // included) and a front of at most output_bytes / 8 values.
  std::uint64_t output_bytes = kDefaultOutputBytes;
};

struct ParsedOutput {
  std::vector<double> costs;  // vector after vector
  std::uint64_t vectors = 0;
  ReportedStatistics statistics;
  // The solver's own statement that it did not finish (its log says it timed out, ran out of
  // memory or failed): recorded as that status with no front, whatever it printed. nullopt: it
  // finished (a front, or none: disconnected).
  std::optional<QueryStatus> stated_status;
  std::string stated;  // the statement, for the journal's message
};

// Reads a solver's output; throws mosb::Error (naming the file) when it is unreadable, which makes
// the query `failed`.
using OutputAdapter = std::function<ParsedOutput(const SolverOutputFiles&)>;
// The solver protocol (spec/RUN.md §3): the front from stdout or {front}, statistics from stderr.
ParsedOutput read_protocol_output(const SolverOutputFiles& files);

// The result of one query as the journal keeps it.
struct QueryRecord {
  std::uint64_t query = 0;
  QueryStatus status = QueryStatus::not_run;
  std::vector<double> costs;
  QueryStatistics statistics;  // as the solution file takes them for `status`
  double wall_seconds = 0, cpu_seconds = 0;
  std::optional<std::uint64_t> peak_memory_bytes;
  std::string message;                   // why a query failed or did not finish
  std::vector<std::string> stderr_tail;  // the solver's last lines of stderr (failed queries)
};

struct RunConfig {
  const GraphReader* instance = nullptr;  // opened by the caller (checksums verified)
  std::string instance_path;              // what {instance} becomes
  ViewChoice choice;
  std::string solver_template;
  std::string output_format = "protocol";  // recorded; `adapter` reads it
  OutputAdapter adapter;                   // empty: read_protocol_output
  ProcessLimits limits;
  // The exit statuses that mean the solver finished (EMOA* exits 1 when it has); others fail.
  std::vector<int> success_exit_codes{0};
  // The ε the solver claims (solution.epsilon, spec/EVALUATION.md §2 form): "0", exact, makes a
  // front with a vector another dominates a failure, and eval judges the file by it.
  std::string epsilon = "0";
  unsigned jobs = 1;
  bool pin = false;
  unsigned threads = 1;  // what {threads} becomes
  // nullopt: the best this process can use, cgroup_v1 when a child group can be created in its
  // memory cgroup, else rlimit_poll.
  std::optional<Measurement> measurement;
  // sealed: refused before any solver starts where the kernel cannot seal a query.
  Seal seal = Seal::sealed;
  bool resume = false;
  // With resume: run on although the solver's executable is not the one the journal records
  // (both digests are then recorded); without it such a journal is refused.
  bool allow_new_executable = false;
  std::optional<Shard> shard;  // run only this shard's queries; the file records it (run.shard)
  std::string solver_name, solver_version;  // name empty: the executable's file name
  // What {source} and {target} add to the stored 0-based ids: 1 for a solver that reads the text
  // a profile prepared in base 1 (the text and the ids come from the same profile field).
  unsigned id_base = 0;
  // More of what the run is (a solver profile's name, repository, options, scale), recorded as
  // the solver's parameters and bound into the journal.
  std::map<std::string, std::string> parameters;
  std::string output;  // the solution file; the journal is OUTPUT.journal
  // SHA-256 (hex) of a file: the executable's digest for the metadata.
  std::function<std::string(const std::string&)> sha256_file;
};

struct RunProgress {
  std::uint64_t done = 0, total = 0;
  StatusCounts counts;
  double elapsed_seconds = 0;   // of this invocation
  std::uint64_t done_here = 0;  // queries finished by this invocation (for an ETA)
};

struct RunCallbacks {
  std::function<void(const RunProgress&)> progress;
  std::function<void(const QueryRecord&, const Query&)> failed;
};

// The reasons a run's queries did not complete (failed, timeout, memory-limit: QueryRecord's
// message with a leading FILE:LINE[:COLUMN] location taken off, so that one cause counts once
// whatever query gave it), each with how many queries gave it.
using FailureReasons = std::map<std::string, std::uint64_t>;
// The reason most queries gave (the first in order on a tie) and their number; nullopt for none.
std::optional<std::pair<std::string, std::uint64_t>> most_common_failure(
    const FailureReasons& reasons);

struct RunResult {
  bool interrupted = false;
  // total: the queries this run is for (all of the set, or the shard's); `counts` are theirs.
  std::uint64_t total = 0, from_journal = 0, ran = 0;
  std::uint64_t query_set_size = 0;
  StatusCounts counts;
  FailureReasons failures;                   // of every query that did not complete
  double wall_seconds = 0, cpu_seconds = 0;  // of the solvers run by this invocation
  Measurement measurement = Measurement::rlimit_poll;
  std::string journal;
};

// The journal of `output`.
std::string journal_path(const std::string& output);
// How many query records the journal at `journal` holds, for a progress report (`experiment
// status`, `run --slurm --status`): its whole lines past the first that are query records (not
// a changed executable's line, not a torn last line); 0 when it is absent. No check: the run
// that resumes it checks every line.
std::uint64_t journaled_queries(const std::string& journal);

// The instance a run maps (header and table checked, every checksum verified): a packed file is
// refused with one line saying how to get one a solver can map (mosb unpack, mosb store
// instance), since every solver would fail on it.
GraphReader open_run_instance(const std::string& path);

// Runs the queries `config` selects (those the journal lacks, with resume). Throws mosb::Error
// (invalid_argument for a bad template or a journal of another run, io for the file system) before
// any solver starts; after that, a solver's problems are query statuses. With `stop` set, the
// running solvers are killed, the journal kept, nothing written, and interrupted is true.
RunResult run_solver(const RunConfig& config, const RunCallbacks& callbacks,
                     const std::atomic<bool>& stop);

}  // namespace mosb
