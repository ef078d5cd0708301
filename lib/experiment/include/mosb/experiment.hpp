// `mosb experiment` (spec/EXPERIMENT.md): a matrix of solvers × instances × views run into one
// results directory. The experiment arrives as a plain struct (converters/experiment parses the
// TOML file); plan_experiment resolves it against the store or instance files into cells, each a
// `mosb run` (lib/run's run_solver: its measurement, statuses and journal) writing one solution
// file; results/MANIFEST lists the finished cells. A rerun continues: a finished cell is not run
// again, a killed one resumes from its journal, and a cell whose solver executable or limits
// changed is refused, by name, before anything runs.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mosb/enum_names.hpp"
#include "mosb/run.hpp"
#include "mosb/slurm.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solver_spec.hpp"

namespace mosb {

// Where a value came from in the experiment file, for one-line errors
// "FILE:LINE:COLUMN: key 'KEY': problem".
struct SourceLine {
  std::size_t line = 0;  // 0: unknown
  std::string key;
  std::size_t column = 0;  // 0: unknown
};

struct ExperimentSolver {
  std::string name;  // [A-Za-z0-9_.+-]: a directory name under results/cells; also spec.name
  // A template with its output format, or a profile with its executable and options; and ε.
  SolverSpec spec;
  // Optional: the solver runs only the cells these patterns match (as Experiment::benchmarks), a
  // bi-objective solver the 2-objective views; each must match a cell of the experiment.
  std::vector<std::string> benchmarks;
  std::vector<SourceLine> benchmark_sources;
  SourceLine source;
};

struct ExperimentLimits {
  ProcessLimits process;  // time, memory, cpu, grace, output
  std::string text;       // the limits as the file wrote them, canonical: what a rerun compares
};

// `[[benchmark_limits]]`: other limits for the cells some benchmark patterns match (the paper's
// memory caps for DIMACS-Extended and Grid_3 only), the experiment's limits with these keys
// replaced.
struct BenchmarkLimits {
  std::vector<std::string> benchmarks;  // patterns, as Experiment::benchmarks
  std::vector<SourceLine> benchmark_sources;
  ExperimentLimits limits;  // complete: the experiment's, overridden
  SourceLine source;
};

struct Experiment {
  std::string file;  // the experiment file, for errors
  std::string name;
  std::filesystem::path store;  // or instances
  std::vector<std::filesystem::path> instances;
  std::vector<std::string> benchmarks;        // view or benchmark names, shell patterns
  std::vector<SourceLine> benchmark_sources;  // per benchmarks entry
  SourceLine store_source;
  ExperimentLimits limits;
  std::vector<BenchmarkLimits> benchmark_limits;  // the first whose patterns match a cell wins
  std::vector<ExperimentSolver> solvers;
  std::vector<std::string> reference_solvers;
  SourceLine reference_source;
  // The benchmarks were narrowed on the command line (restrict_benchmarks): a solver's or a
  // [[benchmark_limits]] pattern may then match no cell (a laptop run of the paper's file).
  bool restricted = false;
  // The command line's narrowing as given (`--store DIR`, `--benchmarks ...`, `--time-limit T`,
  // `--executable NAME=PATH`): recorded with the plan, so that `experiment status` can say the
  // whole command that continues the run.
  std::vector<std::string> command_line;
};

// "FILE:LINE:COLUMN: key 'KEY': problem" (mosb::source_error: without what is unknown), as every
// refusal of an experiment file and of its plan says.
std::string experiment_error(const Experiment& e, const SourceLine& at, const std::string& problem);

// Gives the solver `name` the executable `path` (`--executable NAME=PATH`: one experiment file
// for every machine); a sweep's name (`apex` of apex-eps0.01, ...) gives it to every ε of it.
// Throws mosb::Error (invalid_argument) when no solver has that name.
void set_solver_executable(Experiment& e, const std::string& name, const std::string& path);
// The command line's narrowing of an experiment (`experiment run --benchmarks`, `--time-limit`):
// only the cells these patterns match (each must match one, as the file's benchmarks must); the
// time limit of every cell, the file's [[benchmark_limits]] included. A refusal of a pattern names
// `source` as its key (the caller's name for where the patterns came from).
void restrict_benchmarks(Experiment& e, const std::vector<std::string>& patterns,
                         const std::string& source);
void set_time_limit(Experiment& e, double seconds);

// One cell: one solver over the query set of one view of one instance.
struct ExperimentCell {
  std::string solver;    // ExperimentSolver::name
  std::string instance;  // the file's name without .mosb
  std::string view, query_set;
  std::string instance_digest;
  std::string instance_file;  // the store entry or instance file
  std::uint64_t queries = 0;
  std::string file;  // cells/SOLVER/INSTANCE.VIEW.sol, relative to the results directory
  // 0: the experiment's limits; k > 0: those of its benchmark_limits[k - 1] (cell_limits)
  std::size_t limits = 0;
  std::string id() const { return solver + "/" + instance + "/" + view; }
};

struct ExperimentPlan {
  Experiment experiment;
  SolverResolver resolver;                     // what the solvers were checked with, and run by
  std::vector<ResolvedSolver> solvers;         // per solver: executable, binding
  std::vector<std::string> executable_sha256;  // per solver: its executable's SHA-256
  std::vector<ExperimentCell> cells;           // solver-major, then instance, then view
  // What the plan did that the file alone does not say: a solver that runs no cell of a run
  // narrowed by --benchmarks.
  std::vector<std::string> notes;
};

// The limits a cell runs under (ExperimentCell::limits). `cell` must be of the plan's experiment.
const ExperimentLimits& cell_limits(const ExperimentPlan& plan, const ExperimentCell& cell);
// The largest limits of any cell (a SLURM array's request): the longest time and grace, and the
// largest memory, none (0) when some cell has none.
ProcessLimits largest_cell_limits(const ExperimentPlan& plan);

// Resolves the experiment: the store (or instance files), the benchmarks each matching some
// (instance, view) (a pattern matches a view name, a benchmark name or BENCHMARK/VIEW), and each
// pattern of benchmark_limits some cell, giving each cell its limits, every
// solver checked by `resolver` (converters/profiles' solver_resolver() for the program), the
// reference solvers among the solvers. Throws mosb::Error (invalid_argument) with
// experiment_error's line before anything runs.
ExperimentPlan plan_experiment(const Experiment& experiment, const SolverResolver& resolver);

// One record of results/MANIFEST: a finished cell.
struct CellRecord {
  ExperimentCell cell;
  std::string sha256;             // of the solution file
  std::string executable_sha256;  // of the solver's executable when it ran
  std::string solver_binding;     // ResolvedSolver::binding
  std::string limits;
  StatusCounts counts;
};

inline constexpr std::string_view kResultsManifestFormat = "mosb-experiment-results";
// results/MANIFEST's records, sorted by cell id; empty when there is none. Throws mosb::Error
// naming the file and line on one that does not parse.
std::vector<CellRecord> read_results_manifest(const std::filesystem::path& results);

enum class CellState {
  done,     // listed in MANIFEST, its file there with the listed SHA-256
  running,  // a journal, and the experiment's lock held by a running process
  stopped,  // a journal, nobody running it: the next run resumes it
  missing,  // neither
  failed,   // done, with failed queries (the solver crashed or its output was unreadable)
  damaged,  // listed, but the file is absent or not the listed bytes
};
inline constexpr auto kCellStateNames = enum_names<CellState>({
    {CellState::done, "done"},
    {CellState::running, "running"},
    {CellState::stopped, "stopped"},
    {CellState::missing, "missing"},
    {CellState::failed, "failed"},
    {CellState::damaged, "damaged"},
});
std::string_view to_string(CellState state);

struct CellStatus {
  ExperimentCell cell;
  CellState state = CellState::missing;
  StatusCounts counts;          // done and failed: the file's
  std::uint64_t journaled = 0;  // running and stopped: queries the journal holds
  std::string detail;           // damaged: why
};

// Every cell of the experiment results/ holds (results/experiment.json, written by
// run_experiment), in plan order. Throws mosb::Error naming the directory when it holds none.
std::vector<CellStatus> experiment_status(const std::filesystem::path& results);

struct ExperimentProgress {
  std::uint64_t cells_done = 0, cells_total = 0;
  std::uint64_t queries_done = 0, queries_total = 0;
  std::uint64_t queries_done_here = 0;  // by this invocation, for an ETA
  StatusCounts counts;                  // of the queries done
  double elapsed_seconds = 0;
  std::string cell;  // the one running
};

struct ExperimentOptions {
  unsigned jobs = 1;  // queries at once within a cell
  std::optional<Measurement> measurement;
  Seal seal = Seal::sealed;
  std::function<void(const ExperimentProgress&)> progress;
  std::function<void(const ExperimentCell&, const QueryRecord&, const Query&)> failed;
};

struct ExperimentResult {
  std::uint64_t cells = 0, ran = 0, skipped = 0;  // skipped: done before
  // Of the cells run: those a killed run had begun, and the queries taken from their journals.
  std::uint64_t resumed = 0, queries_from_journal = 0;
  StatusCounts counts;      // every cell's
  FailureReasons failures;  // of the cells run now (RunResult::failures, added up)
  bool interrupted = false;
};

// Runs every cell not done into results/ (created, with the plan recorded in
// results/experiment.json). Refuses, before anything runs, naming every such cell: a done cell
// whose executable or limits changed (remove its file to run it again), a damaged one, and a
// results directory of another experiment. A packed store entry is run on the store's unpacked
// copy (Store::instance). MANIFEST is rewritten atomically after each cell. With `stop` set, the
// running cell keeps its journal and the run returns interrupted.
ExperimentResult run_experiment(const ExperimentPlan& plan, const std::filesystem::path& results,
                                const ExperimentOptions& options, const std::atomic<bool>& stop);

// --- One SLURM job array for the whole matrix (spec/EXPERIMENT.md §4).

// The experiment's cells as array tasks: consecutive cells (plan order) packed while a task holds
// at most `queries_per_task` queries; a cell of more queries is a task of its own. Deterministic:
// every task recomputes the packing from the plan. Throws mosb::Error (invalid_argument) for 0.
std::vector<std::vector<std::size_t>> experiment_tasks(const ExperimentPlan& plan,
                                                       std::uint64_t queries_per_task);
// The queries of the plan's `cells`.
std::uint64_t queries_of(const ExperimentPlan& plan, const std::vector<std::size_t>& cells);
// The plan of task `index` (1-based) of `tasks`: the same experiment, its cells only.
ExperimentPlan task_plan(const ExperimentPlan& plan,
                         const std::vector<std::vector<std::size_t>>& tasks, std::uint64_t index);

// What a task's results directory holds, in the states of lib/run's SLURM shards: done (every
// cell of the task listed and intact), partial (some cells or a journal), missing (nothing),
// damaged (a listed cell's file is not the listed bytes).
struct TaskFiles {
  ShardFile state = ShardFile::missing;
  std::uint64_t cells_done = 0, queries_done = 0;
  StatusCounts counts;
  std::string problem;
};
TaskFiles task_files(const ExperimentPlan& task, const std::filesystem::path& directory);

// The kind of an experiment's job array (SlurmRun::kind): task i runs task i of the experiment's
// cells (`mosb experiment run EXP --task i/N`, spec/EXPERIMENT.md §4) into DIR/task-i/, a results
// directory of its own.
inline constexpr std::string_view kExperimentKind = "experiment";

// The job array of experiment `file` (its absolute path) in tasks of at most `queries_per_task`
// queries: `run` (slurm_run_here's, with the caller's account, partition, jobs and task
// arguments) given its kind, file, task and query counts and the largest of the cells' limits,
// which every task requests. Returns the tasks; throws mosb::Error when there are none.
std::vector<std::vector<std::size_t>> plan_experiment_array(SlurmRun& run,
                                                            const ExperimentPlan& plan,
                                                            const std::string& file,
                                                            std::uint64_t queries_per_task);
// The tasks of the existing array `run` (read_slurm_directory(DIR, kExperimentKind)), checked
// to be experiment `file`'s as the file now plans them (the same file, its --queries-per-task
// making run.shards tasks); throws mosb::Error naming what differs.
std::vector<std::vector<std::size_t>> experiment_array_tasks(const SlurmRun& run,
                                                             const ExperimentPlan& plan,
                                                             const std::string& file);
// Each task's state (task_files of DIR/task-i) and the scheduler's (slurm_status).
SlurmStatus experiment_array_status(const SlurmRun& run, const ExperimentPlan& plan,
                                    const std::vector<std::vector<std::size_t>>& tasks);
// DIR/task-i, where array task i writes its results.
std::filesystem::path experiment_task_directory(const SlurmRun& run, std::uint64_t task);

// Merges the finished cells of task results directories into `results` (created as
// run_experiment creates it, the plan recorded): each cell of the plan that `results` does not
// list and a part does is copied (its SHA-256 checked against the part's MANIFEST record) and
// listed. Refuses, before copying anything, as run_experiment refuses a rerun: a part's cell whose
// executable, template, limits or instance are not the plan's, or whose file is not the listed
// bytes. Returns the cells merged.
std::uint64_t merge_experiment_results(const ExperimentPlan& plan,
                                       const std::filesystem::path& results,
                                       const std::vector<std::filesystem::path>& parts);

// The experiment file the last run of `results` read (absolute), its command line's narrowing, its
// name, limits and solvers, as results/experiment.json records them; an empty file when it records
// none.
struct RecordedRun {
  std::string file;
  std::vector<std::string> arguments;
  // What the plan recorded of the experiment: its name, limits ("time=24h memory=..."; per
  // benchmark limits follow) and each solver as it ran (empty for an older experiment.json).
  struct Solver {
    std::string name, binding, executable_sha256;
  };
  std::string name, limits;
  std::vector<Solver> solvers;
};
RecordedRun recorded_run(const std::filesystem::path& results);
// The solution files of a results directory (its MANIFEST's, in the plan's cell order), or `path`
// itself when it is a file: what `solutions reference`, `eval` and `report` take for RESULTS. A
// listed cell that the last run's plan (results/experiment.json) no longer has, its solver or
// benchmark since removed from the file, is left out, its id added to `left_out`.
std::vector<std::filesystem::path> result_files(const std::filesystem::path& path,
                                                std::vector<std::string>* left_out = nullptr);
// The instance files of a results directory's cells (results/experiment.json), each once, in cell
// order: what `mosb report RESULTS` reports on.
std::vector<std::filesystem::path> result_instances(const std::filesystem::path& results);
// Per instance (content digest) the views a results directory's cells ran (results/
// experiment.json): what `mosb report RESULTS` reports its instances by.
std::map<std::string, std::set<std::string>> result_views(const std::filesystem::path& results);
// A reference directory's solution files (*.sol, sorted by name), or `path` itself when it is a
// file (`--reference REFS/`).
std::vector<std::filesystem::path> reference_files(const std::filesystem::path& path);
// The references `source` holds for the instances of these content digests: a store (a directory
// with a MANIFEST) gives its exact solution file of each, checked against its entry
// (Store::references), and names in `missing` the instances it has none for; a solution file or
// a directory of them gives every file (reference_files), `missing` empty.
struct ReferenceFiles {
  std::vector<std::filesystem::path> files;
  std::vector<std::string> missing;  // content digests, sorted
};
ReferenceFiles reference_files_for(const std::filesystem::path& source,
                                   const std::set<std::string>& instance_digests);

}  // namespace mosb
