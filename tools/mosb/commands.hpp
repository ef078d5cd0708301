// One function per subcommand: each registers its options on the CLI11 app and returns what to run
// when that subcommand is chosen; `run` returns the process exit code.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/eval.hpp"
#include "mosb/pack.hpp"
#include "mosb/run.hpp"
#include "mosb/solution_eval.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_summary.hpp"
#include "mosb/views.hpp"

namespace CLI {
class App;
class Option;
class Validator;
}  // namespace CLI

namespace mosb::converters {
struct SuiteEntry;
}

namespace mosb {
struct FileCheck;
class GraphReader;
}  // namespace mosb

namespace mosb::converters {
struct TerrainRules;
}

namespace mosb::cli {

struct Command {
  CLI::App* subcommand;
  std::function<int()> run;
};

// A usage mistake found only after parsing (say, neither of two alternative options): exit code 2
// and a one-line message, like the option parser's own errors (main.cpp).
class UsageError : public Error {
 public:
  using Error::Error;
};

// The flag that sets the library's setting `setting` (MessagePart): "--queries-per-task" for
// "queries_per_task"; a setting no flag sets keeps its library name.
std::string flag_of_setting(std::string_view setting);
// A library error as the program says it: the settings it names spelled as flags.
std::string error_text(const Message& message);
std::string error_text(const Error& error);

// The one parser of every option that takes an unsigned integer: the whole text is decimal digits
// (no sign, space, exponent or hex) and the value is at most `max`, so nothing wraps or saturates.
// The message names the option (CLI11 prefixes it) and says why; exit code 2.
// `max` is usually the target's std::numeric_limits<T>::max().
CLI::Validator unsigned_integer(std::uint64_t max);
// The one parser of every option that takes a non-negative real (a double): the whole text is a
// decimal number (exponent allowed), finite and >= 0.
CLI::Validator non_negative_real();
// The one parser of every option that takes a memory size: parse_memory_size (mosb/run.hpp), the
// grammar of an experiment file's sizes too; the text becomes the count of bytes.
CLI::Validator memory_size();
// Every option that takes a duration: parse_duration (mosb/run.hpp), 60, 60s, 500ms, 2m, 1h.
CLI::Validator duration();
// `--reference SOURCE`: a path that exists, or a published store's URL (is_store_url).
CLI::Validator reference_source();
// `--isolation seal|none` of `mosb run` and `mosb experiment run` (spec/RUN.md §4.1): its default
// is $MOSB_ISOLATION when set (a cluster's or a test suite's), else seal.
CLI::Option* add_isolation_option(CLI::App* subcommand, std::string& isolation);
// The choice, or a UsageError naming $MOSB_ISOLATION when that holds none of the words.
Seal parse_isolation(const std::string& isolation);
// `--measurement auto|...` of `mosb run` and `mosb experiment run`: how memory is limited and
// measured (kMeasurementNames; auto, the default: the first that works).
CLI::Option* add_measurement_option(CLI::App* subcommand, std::string& measurement);
// The measurement chosen: nullopt for auto.
std::optional<Measurement> chosen_measurement(const std::string& measurement);

// Makes SIGINT, SIGTERM and SIGHUP (a closed terminal) set the returned flag, the stop request
// `run` and `experiment run` pass their library, which ends the running solvers, keeps the
// journal and returns; and ignores SIGPIPE, so that a closed pipe on stdout (mosb run ... |
// head -1) makes a write fail instead of killing mosb before it removes its temporaries.
const std::atomic<bool>& install_stop_handlers();

// `--slurm DIR` and the options of a SLURM job array, the same for `mosb run` (spec/RUN.md §8)
// and `mosb experiment run` (spec/EXPERIMENT.md §4): --queries-per-task, --throttle,
// --account, --partition, --submit and --status.
struct SlurmArgs {
  std::string directory, account, partition;
  std::optional<std::uint64_t> queries_per_task;
  unsigned throttle = 0;
  bool submit = false, status = false;
};
struct SlurmHelp {
  std::string slurm;             // what --slurm DIR writes
  std::string queries_per_task;  // how --queries-per-task K makes tasks
  std::string status;            // what --status shows
};
// Registers the options; returns --queries-per-task's (which `run` makes exclude --shards).
CLI::Option* add_slurm_options(CLI::App* subcommand, SlurmArgs& slurm, const SlurmHelp& help);
// Every option that takes an ε: a non-negative decimal as parse_epsilon (mosb/eval.hpp) reads it,
// the form spec/EVALUATION.md §2 allows and `solution.epsilon` stores.
CLI::Validator epsilon_value();
// A comma-separated list of ε (`--eps` of eval and report), each as epsilon_value takes one;
// throws UsageError naming the item.
std::vector<Ratio> parse_epsilons(const std::string& list);
// An experiment's results directory's solution files (mosb::result_files), or the path itself when
// it is a file; a line on stderr names the listed cells it leaves out (no longer in the
// experiment).
std::vector<std::filesystem::path> experiment_result_files(const std::filesystem::path& path);
// The references `--reference SOURCE` gives for these instances (reference_files_for): a solution
// file, a directory of them, a store, or a store's URL, whose references of these instances are
// pulled first (with the instances they are checked against) into store_cache(URL). A line on
// stderr names each instance a store has no reference for.
std::vector<std::filesystem::path> reference_files_of(const std::string& source,
                                                      std::span<const GraphReader> instances);

// `--runtime wall|reported` of every command that summarises runtimes (unset: choose_runtime's
// default), and with `--tolerance REL` of every command that compares solution files (`eval`,
// `solutions compare`, `solutions reference`; in solutions_compare.cpp), into the library's
// ComparisonOptions.
void add_runtime_option(CLI::App* subcommand, std::optional<RuntimeSource>& runtime);
void add_comparison_options(CLI::App* subcommand, ComparisonOptions& options);
// Free text that ends up in text, JSON and SVG output (--solver, --title, ...): no control
// character, so a newline cannot forge a line of text output and a NUL or escape cannot reach SVG.
CLI::Validator printable_text();

// Query counts per status as every command prints them: "3 solved, 0 timeout, ..." for every
// status, or with `nonzero` only those with a count.
std::string status_counts_text(const StatusCounts& counts, bool nonzero);
// 3 (after a line on stderr naming the most common reason) when queries ran and none completed,
// else 0: the exit status of `run` and `experiment run` once they finished (spec/RUN.md §9).
int no_query_completed(const StatusCounts& counts, const FailureReasons& failures);

class JsonWriter;
// The counts as a JSON object keyed by status name (after the caller's key).
void json_status_counts(JsonWriter& json, const StatusCounts& counts);
// A distribution as a JSON object (count, median, mean, max; min with `with_min`, the shifted
// geometric mean with `runtime`), or null.
void json_distribution(JsonWriter& json, const std::optional<Distribution>& d, bool with_min,
                       bool runtime);
// "[min A, ]median B, mean C, max D" with `unit` after each value, or "none".
std::string distribution_text(const std::optional<Distribution>& d, const char* unit,
                              bool with_min = false);

// Registers `--json` (the report as one JSON object on stdout) on a reporting command.
void add_json_flag(CLI::App* subcommand, bool& json);

// `--max-memory SIZE` of every command that decodes packed files: the most memory decoding one
// may take (a number of bytes, or with a unit: 512M, 4G; powers of 1024). 0, the default: the
// memory the system reports available. A file that would need more is refused before anything
// is allocated (mosb::unpack_bytes).
CLI::Option* add_max_memory_option(CLI::App* subcommand, std::uint64_t& max_memory);
// --check-memory: the working memory of each file's check as a store takes it in.
CLI::Option* add_check_memory_option(CLI::App* subcommand, std::uint64_t& check_memory);
// --check-disk: the most disk that check may spill to; absent, mosb::default_check_disk (a factor
// of the file's size or of --check-memory).
CLI::Option* add_check_disk_option(CLI::App* subcommand, std::optional<std::uint64_t>& check_disk);

// `--id-base 0|1`, the same everywhere: the id of the first vertex in the text files a command
// reads or writes (the instance itself is always 0-based). `default_text` says what applies
// when the option is absent (check the returned option's count()).
CLI::Option* add_id_base_option(CLI::App* subcommand, unsigned& id_base,
                                const std::string& default_text);

// `--id-base 0|1` with `--force-id-base`, for a command whose text files concern an existing
// instance: an explicit --id-base contradicting the id_base the instance's metadata records is
// refused (an off-by-one in every vertex id would otherwise pass silently), unless forced.
struct InstanceIdBase {
  unsigned value = 0;
  bool force = false;
  CLI::Option* option = nullptr;
  // The explicit --id-base, nullopt when absent; throws UsageError (exit 2) on a contradiction.
  std::optional<unsigned> checked(const GraphReader& instance) const;
};
void add_instance_id_base_options(CLI::App* subcommand, InstanceIdBase& id_base,
                                  const std::string& default_text);

// `--seed S`, the same for every generator: the seed of the specified random stream, default 1.
CLI::Option* add_seed_option(CLI::App* subcommand, std::uint64_t& seed, const std::string& what);

// The `-o,--output` option of a command that writes a file (or, for `export`, a directory).
CLI::Option* add_output_option(CLI::App* subcommand, std::string& output, const std::string& what);

// `--expect-digest D` of every `convert` and `generate` command: the content digest (32 hex
// digits, FORMAT.md §8) the written file must have; with another, nothing is written
// (spec/MANIFEST.md, "Proving a conversion"). Upper-case digits are taken as lower-case.
CLI::Option* add_expect_digest_option(CLI::App* subcommand, std::string& digest);

// `--view NAME=OBJ1,OBJ2,...[@SET]` (repeatable) of every `convert` and `generate` command: views
// written besides (or, with a default view's name, instead of) the family's default views.
CLI::Option* add_view_spec_option(CLI::App* subcommand, std::vector<std::string>& specs);
// The converter's output with the --view texts added (mosb::add_views); throws on a bad text.
template <class Graph>
Graph with_views(Graph graph, const std::vector<std::string>& specs) {
  std::vector<ViewSpec> views;
  views.reserve(specs.size());
  for (const auto& text : specs) views.push_back(parse_view_spec(text));
  add_views(graph, views);
  return graph;
}

// `--view NAME`, `--objectives A,B,...` and `--queries SET` of every command that reads a view:
// the same choice everywhere, resolved by mosb::select_view. `what` says what the command does
// with the objectives (the --view help).
void add_view_choice_options(CLI::App* subcommand, ViewChoice& choice, const std::string& what);

// --swamp and --water, the Moving AI terrain options of `convert guards` and `convert movingai`.
struct TerrainOptions {
  std::string swamp = "passable";
  std::string water = "blocked";
  converters::TerrainRules rules() const;
};
void add_terrain_options(CLI::App* subcommand, TerrainOptions& terrain);

// A subcommand with one child per family (`convert dimacs`, `generate grid`, ...): runs the chosen
// one.
Command group(CLI::App* parent, std::vector<Command> children);

// Prints "wrote FILE: n vertices, m arcs, d objectives, digest D" after reopening FILE, or with
// `json` {"file", "vertices", "arcs", "objectives", "digest"}; returns 0.
int report_written(const std::string& path, bool json);

class JsonWriter;

// Prints "wrote N FAMILY instances and MANIFEST to DIR", or with `json` {"directory",
// "instances": [{"name", "file", "size", "digest"}, ...]} and whatever keys `more` adds; returns 0.
int report_suite(const std::string& directory, const std::string& family,
                 const std::vector<converters::SuiteEntry>& entries, bool json,
                 const std::function<void(JsonWriter&)>& more = {});

// A suite's files packed at the default level (a published suite has one fixed level), or not.
std::optional<PackOptions> suite_pack(bool pack);
// `--pack` for `generate ... --suite`.
CLI::Option* add_suite_pack_flag(CLI::App* sub, bool& pack);

// The per-file report of a store or manifest check (store.cpp): "OK   FILE" or one "FAIL KIND:
// DETAIL" line per problem and a count, or with `json` {"ok", "files": [{"file", "ok",
// "problems": [{"kind", "detail"}]}]}; returns 0 when every file is ok, else 1.
int report_checks(const std::vector<FileCheck>& checks, bool json);

Command add_inspect(CLI::App& app);
Command add_verify(CLI::App& app);
Command add_generate(CLI::App& app);
Command add_convert(CLI::App& app);
Command add_queries(CLI::App& app);  // queries.cpp: `queries import` and `queries generate`
Command add_stats(CLI::App& app);
Command add_export(CLI::App& app);     // export_dimacs.cpp: the `export` group and its children
Command add_store(CLI::App& app);      // store.cpp: `store init|add|list|verify`
Command add_suite(CLI::App& app);      // suite_build.cpp: `suite build`
Command add_plot(CLI::App& app);       // plot.cpp: `plot correlation`, `plot map`
Command add_solutions(CLI::App& app);  // solutions.cpp: `solutions import|export|inspect|verify`
Command add_solutions_compare(CLI::App* solutions);    // solutions_compare.cpp: `solutions compare`
Command add_solutions_merge(CLI::App* solutions);      // solutions_merge.cpp: `solutions merge`
Command add_eval(CLI::App& app);                       // eval.cpp: `eval`
Command add_pack(CLI::App& app);                       // pack.cpp: `pack`
Command add_run(CLI::App& app);                        // run.cpp: `run`
Command add_report(CLI::App& app);                     // report.cpp: `report`
Command add_cache(CLI::App& app);                      // cache.cpp: `cache clear`
Command add_experiment(CLI::App& app);                 // experiment.cpp: `experiment run|status`
Command add_solutions_reference(CLI::App* solutions);  // solutions_reference.cpp
Command add_unpack(CLI::App& app);                     // pack.cpp: `unpack`

// Children of `generate`.
Command add_generate_grid(CLI::App& generate);
Command add_generate_netmaker(CLI::App& generate);

// Children of `convert`, one line a source family: `X(NAME)` is `mosb convert NAME`, defined by
// add_convert_NAME in convert_NAME.cpp (docs/ARCHITECTURE.md, "A new source family").
#define MOSB_CONVERT_FAMILIES(X) X(dimacs) X(netmaker) X(fmi) X(guards) X(movingai) X(roadmap)
#define MOSB_DECLARE_CONVERT(name) Command add_convert_##name(CLI::App& convert);
MOSB_CONVERT_FAMILIES(MOSB_DECLARE_CONVERT)
#undef MOSB_DECLARE_CONVERT

}  // namespace mosb::cli
