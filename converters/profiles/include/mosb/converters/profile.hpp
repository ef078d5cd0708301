// Solver profiles (spec/RUN.md §10): a small TOML file that says everything `mosb run` needs to
// run one published solver unmodified: the input it reads (the instance, or a DIMACS text form
// mosb prepares, in the id base it expects), its command line, how it takes a time limit and ε,
// its options, and how its output is read. This header is the plain struct and its parser; the
// shipped profiles (profiles/*.toml) are embedded in the program.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/converters/dimacs_export.hpp"
#include "mosb/enum_names.hpp"
#include "mosb/solution_file.hpp"

namespace mosb::converters {

// What the solver reads.
enum class InputForm { mosb, dimacs, dimacs_multi_column };
inline constexpr auto kInputFormNames = enum_names<InputForm>({
    {InputForm::mosb, "mosb"},
    {InputForm::dimacs, "dimacs"},
    {InputForm::dimacs_multi_column, "dimacs-multi-column"},
});

// How the solver's loader treats arcs with the same tail and head.
enum class ParallelArcs { keep, collapse };
inline constexpr auto kParallelArcsNames = enum_names<ParallelArcs>({
    {ParallelArcs::keep, "keep"},
    {ParallelArcs::collapse, "collapse"},
});

// Where a line of the solver's output is read.
enum class OutputFile { front, stdout_file, stderr_file };
inline constexpr auto kOutputFileNames = enum_names<OutputFile>({
    {OutputFile::front, "front"},
    {OutputFile::stdout_file, "stdout"},
    {OutputFile::stderr_file, "stderr"},
});

struct ProfileInput {
  InputForm form = InputForm::mosb;
  unsigned id_base = 0;
  bool integer_costs = false;
  std::optional<std::uint64_t> max_arc_cost;
  std::optional<std::uint64_t> max_degree;  // in- and out-degree
  ParallelArcs parallel_arcs = ParallelArcs::keep;
  bool append_dummy_arc = false;
  unsigned pad_columns = 0;                     // dimacs-multi-column: exactly this many columns
  std::optional<QueriesFormat> queries_format;  // when the command uses {queries}
  unsigned min_objectives = 1, max_objectives = 0;  // 0: no maximum
};

// {time_limit}: mosb's limit L (the larger of --time-limit and --cpu-limit) as L × scale + add,
// rounded up to whole seconds when integer; `unlimited` when mosb has none.
struct ProfileTimeLimit {
  double scale = 1.1, add_seconds = 1;
  bool integer = false;
  double unlimited = 1e9;
};

// A --profile-option KEY=VALUE: {KEY} in the command.
struct ProfileOption {
  std::string name, description, default_value;
  std::vector<std::string> values;  // empty: any value without blanks or braces
  // Values that handle at most this many objectives (BOA*: 2); more are refused.
  std::map<std::string, unsigned> max_objectives;
};

// What the solver's own runtime measures: the time passed, or its CPU time.
enum class RuntimeClock { wall, cpu };
inline constexpr auto kRuntimeClockNames = enum_names<RuntimeClock>({
    {RuntimeClock::wall, "wall"},
    {RuntimeClock::cpu, "cpu"},
});

// A line of the output that says something: a status (`timeout: 1`), or that the solver finished.
struct OutputLine {
  OutputFile file = OutputFile::front;
  std::string text;  // status: the whole line (trailing blanks and \r ignored); finished: prefix
  QueryStatus status = QueryStatus::timeout;  // status lines
  std::string when_option, when_value;        // only when --profile-option when_option=when_value
};

// A value on a line of the output: the line starting with `prefix`, its `field`-th field
// (1-based) split on `separator` (0: the rest of the line after the prefix).
struct OutputField {
  OutputFile file = OutputFile::stdout_file;
  std::string prefix, separator;
  unsigned field = 0;
};

// The solver's runtime: an output field × unit_seconds.
struct OutputRuntime : OutputField {
  double unit_seconds = 1;
};

struct ProfileOutput {
  std::string format = "protocol";  // protocol | example-log | json-log | vectors
  // vectors: the file (a pattern with {front} {fronts} {source} {target}, or "stdout"), the
  // lines that hold a vector (those starting with `prefix`; others are ignored), the bracketed
  // group that is the cost vector (1-based; 0: the text after the prefix), the separator between
  // values and whether one may end the vector.
  std::string file = "{front}";
  std::string prefix;
  unsigned group = 0;
  std::string separator = " ";
  bool trailing_separator = false;
  std::vector<OutputLine> status_lines;
  std::vector<OutputLine> finished;  // a line that must be there, else `unfinished`
  QueryStatus unfinished = QueryStatus::failed;
  std::optional<OutputRuntime> runtime;
  // What the runtime the solver reports (here, or in its log) measures, recorded with the run
  // (profile.runtime_clock) so that a table of reported runtimes says which clocks it mixes.
  RuntimeClock runtime_clock = RuntimeClock::wall;
  // The number of vectors the solver says it found (T-MDA's summary): a front of another size
  // fails the query, so a build that does not print its front is never read as disconnected.
  std::optional<OutputField> count;
};

struct SolverProfile {
  std::string file;  // where it was read from (messages)
  // XXH3-64 of the profile's text, hex: a changed profile changes what a finished run is bound to.
  std::string text_digest;
  std::string name, solver, description, repository, version;
  std::string command;  // a template of words with placeholders (spec/RUN.md §10)
  std::vector<int> success_exit_codes{0};
  ProfileInput input;
  ProfileTimeLimit time_limit;
  std::vector<ProfileOption> options;
  ProfileOutput output;
};

// The placeholders a profile's command may use besides its options: the run's own (spec/RUN.md
// §2) and executable, gr, gr:NAME, multi_gr, queries, co, d, time_limit, epsilon.
std::span<const std::string_view> profile_placeholders();

// Parses profile text. Throws mosb::Error "FILE:LINE:COLUMN: key 'K': what is wrong" on a
// malformed file, an unknown key, a value of the wrong type or out of range, a command that uses
// an undeclared placeholder.
SolverProfile parse_profile(std::string_view text, const std::string& file);

// The profiles shipped with mosb (profiles/*.toml, embedded), by name.
struct ShippedProfile {
  std::string_view name, text;
};
std::span<const ShippedProfile> shipped_profiles();

// A shipped profile's name, or a file's path (anything with a '/' or ending in .toml).
SolverProfile load_profile(const std::string& name_or_path);

}  // namespace mosb::converters
