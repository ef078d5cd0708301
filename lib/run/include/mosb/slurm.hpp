// `mosb run --slurm DIR` (spec/RUN.md §8): a run split into shards (run.hpp's Shard), one SLURM
// job-array task per shard, each task `mosb run ... --shard i/N --resume -o DIR/shard-i.sol`
// against the same instance path. DIR holds run.json (what the run is), run.sbatch (the array
// script, deterministic text), jobs (the array job ids submitted, one a line), and per shard its
// solution file, its journal while it runs, and SLURM's log shard-i.log.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mosb/enum_names.hpp"
#include "mosb/run.hpp"
#include "mosb/solution_file.hpp"

namespace mosb {

// What DIR/run.json records: enough to write the script again, to recognise the shard files, and
// to resubmit.
struct SlurmRun {
  // What task i runs: kRunKind, shard i of a `mosb run` (into DIR/shard-i.sol), or the kind of the
  // component that planned the array (lib/experiment's: task i of an experiment's cells).
  std::string kind = "run";
  std::string directory;          // absolute
  std::string mosb;               // absolute path of the mosb program every task runs
  std::string working_directory;  // absolute; the tasks run there (the template's relative paths)
  // The `mosb run` arguments every task passes, from the instance on (absolute instance path),
  // without --shard, --resume and -o.
  std::vector<std::string> run_arguments;
  // The binding every shard file has (SolutionReader's view of it).
  std::string instance, instance_digest, view, query_set;
  std::vector<std::string> objectives;
  std::uint64_t queries = 0, shards = 1;
  // The queries of the largest task, for its --time; 0: ceil(queries / shards), a run's shards.
  std::uint64_t largest_shard = 0;
  // Per-query limits and per-task resources, for --time, --mem and --cpus-per-task.
  double time_limit_seconds = 0, grace_seconds = 1;
  std::uint64_t memory_limit_bytes = 0;
  unsigned jobs = 1, threads = 1;
  unsigned throttle = 0;  // at most this many tasks at once (%K); 0: no limit
  std::string account, partition;
  // What the script says and runs, set by the planner (describe_run_tasks for a run's shards) and,
  // but for the command, not recorded in run.json, since the script is written once, with the
  // directory: its comment lines ("# ..." each), and the arguments every task gives the mosb
  // program before and after run_arguments, "{task}" in them standing for the task's index.
  std::string task_comment;
  std::vector<std::string> task_command, task_words;
};

inline constexpr std::string_view kRunKind = "run";

// A run's tasks (kind, comment, `mosb run … --shard i/N --resume -o DIR/shard-i.sol`), from its
// directory, shards, queries and query set.
void describe_run_tasks(SlurmRun& run);

// What `mosb run --slurm DIR` asks beyond the run itself.
struct SlurmRequest {
  std::string directory;
  // The options that define the run as every task passes them (from --view on: the instance, and
  // --shard, --resume and -o, are the script's to add).
  std::vector<std::string> run_options;
  std::optional<std::uint64_t> shards, queries_per_task;  // exactly one of them
  unsigned throttle = 0;
  std::string account, partition;
};

// The SLURM run of `config` (whose instance is open and whose choice and template are checked):
// the directory and the instance made absolute, the solver's executable checked, this program's
// own path (every task runs it), the binding, the shard count and the per-task resources. Throws
// mosb::Error: invalid_argument for a solver executable that is not there, or a shard count that
// does not fit the query set; io when this program's path cannot be read.
SlurmRun plan_slurm_run(const RunConfig& config, const SlurmRequest& request);

// A SlurmRun with what every kind records alike: `directory` made absolute (no trailing '/'),
// this program's own path (every task runs it) and the working directory. Throws mosb::Error
// (io) when this program's path cannot be read.
SlurmRun slurm_run_here(const std::string& directory);

// N for `--shards N` or `--queries-per-task K` (ceil(Q / K)) over Q queries; throws mosb::Error
// (invalid_argument) for 0, for more shards than queries, or both or neither given.
std::uint64_t slurm_shard_count(std::uint64_t queries, std::optional<std::uint64_t> shards,
                                std::optional<std::uint64_t> queries_per_task);

// The time limit of one task, in seconds (whole minutes): with S = ceil(Q / N) queries in the
// largest shard run J at a time, ceil(S / J) · (time limit + grace + 10 s) + 5 min; nullopt
// without a time limit (the partition's default applies).
std::optional<std::uint64_t> slurm_time_seconds(const SlurmRun& run);
// "D-HH:MM:SS", SLURM's --time form.
std::string slurm_time_text(std::uint64_t seconds);
// The memory of one task in MiB: J · memory limit + 512 MiB for mosb run itself, rounded up;
// nullopt without a memory limit (the partition's default per CPU applies).
std::optional<std::uint64_t> slurm_memory_mib(const SlurmRun& run);

// The job-array script: the same text for the same SlurmRun. Throws mosb::Error
// (invalid_argument) when the run has no task command.
std::string slurm_script(const SlurmRun& run);
// "1-4", "3,5-7": the shards (ascending, distinct) as an array index list.
std::string slurm_array_list(const std::vector<std::uint64_t>& shards);

// Creates DIR (or uses it when empty) with run.json and run.sbatch. Throws mosb::Error
// (invalid_argument) when DIR already holds a run or its path is no SLURM can take (blanks,
// quotes, backslashes or '%'), io on the file system.
void create_slurm_directory(const SlurmRun& run);
// Reads DIR/run.json, an array of `kind`; throws mosb::Error naming the file, and for an array of
// another kind the command that made it (run.json's `command`), which continues it.
SlurmRun read_slurm_directory(const std::string& directory, std::string_view kind);

std::string shard_output(const SlurmRun& run, std::uint64_t shard);  // DIR/shard-i.sol

enum class ShardFile {
  done,     // DIR/shard-i.sol of this run, every query of the shard with a status
  partial,  // no file yet, a journal with some of the shard's queries (running, or killed)
  missing,  // neither
  damaged,  // a file that is unreadable, of another run, or incomplete
};
inline constexpr auto kShardFileNames = enum_names<ShardFile>({
    {ShardFile::done, "done"},
    {ShardFile::partial, "partial"},
    {ShardFile::missing, "missing"},
    {ShardFile::damaged, "damaged"},
});
std::string_view to_string(ShardFile state);  // kShardFileNames

struct ShardState {
  std::uint64_t index = 0;  // i of i/N
  std::uint64_t queries = 0;
  ShardFile file = ShardFile::missing;
  std::uint64_t recorded = 0;  // done: the shard's queries; partial: the journal's records
  std::string problem;         // damaged: why
  StatusCounts counts;         // done: the shard's statuses
  // The scheduler's view of the shard's latest array task, when squeue or sacct knows it.
  std::string job;      // "JOBID_i"
  std::string state;    // PENDING, RUNNING, COMPLETED, FAILED, TIMEOUT, OUT_OF_MEMORY, ...
  bool queued() const;  // pending, running or about to run again: not to be resubmitted
};

struct SlurmStatus {
  std::vector<ShardState> shards;
  std::vector<std::string> jobs;     // the array jobs submitted (DIR/jobs), oldest first
  std::vector<std::string> sources;  // the scheduler commands that answered: "squeue", "sacct"
};

// What `--resume` does with the shards not done: resubmits those the scheduler no longer holds;
// leaves those still queued (pending, running or about to run again), in shard order.
struct Resubmission {
  std::vector<std::uint64_t> resubmit, queued;
};
Resubmission shards_to_resubmit(const std::vector<ShardState>& shards);

// The shard files' states, and the scheduler's (squeue, sacct) when those programs exist.
// `file_state` says what task i (1-based) has written, for a kind whose outputs lib/run does not
// know (an experiment's task directories); empty: a run's DIR/shard-i.sol.
SlurmStatus slurm_status(const SlurmRun& run,
                         const std::function<ShardState(std::uint64_t)>& file_state = {});

// The sbatch command for `shards` (all: the script's own --array), as argv and as shell text that
// also appends the job id to DIR/jobs (what --submit does).
std::vector<std::string> sbatch_arguments(const SlurmRun& run,
                                          const std::vector<std::uint64_t>& shards);
std::string sbatch_command_text(const SlurmRun& run, const std::vector<std::uint64_t>& shards);
// Runs sbatch for `shards` and appends the job id to DIR/jobs; returns the job id. Throws
// mosb::Error with sbatch's message when sbatch is missing or fails.
std::string submit_shards(const SlurmRun& run, const std::vector<std::uint64_t>& shards);

}  // namespace mosb
