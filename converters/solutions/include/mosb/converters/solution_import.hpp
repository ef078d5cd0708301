// Solver output in the forms in circulation, turned into per-query results for SolutionWriter
// (spec/SOLUTIONS.md §7): a directory of per-query front files, a CSV/TSV table, and the JSON logs
// of PPA*/BOA*-style solvers. Every input error is one line naming the file, with LINE:COLUMN for
// text and the JSON pointer of the offending value for JSON.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/query.hpp"
#include "mosb/solution_file.hpp"

namespace mosb::converters {

enum class RecordMatch {
  position,   // the k-th record (or file/row query id k) is query k of the set
  endpoints,  // a record names its start and goal; it is the query of the set with them
};
inline constexpr auto kRecordMatchNames = enum_names<RecordMatch>({
    {RecordMatch::position, "position"},
    {RecordMatch::endpoints, "endpoints"},
});

struct SolutionImportOptions {
  std::size_t objective_count = 0;  // d: the view's objectives
  // 0-based positions, within each input vector, of the values to keep, in the view's order;
  // empty: every vector must hold exactly d values.
  std::vector<std::size_t> columns;
  unsigned id_base = 0;            // base of query and vertex ids in the input: 0 or 1
  std::uint64_t vertex_count = 0;  // n: endpoints must lie in [id_base, n - 1 + id_base]
  std::span<const Query> queries;  // the query set the results belong to
  RecordMatch match = RecordMatch::position;
  // The status of a front file that holds no vector and states no status (--status-for-empty):
  // disconnected, timeout or failed. failed by default: an empty file is what a crashed or killed
  // solver leaves, so calling it disconnected would credit a crash with a proof.
  QueryStatus status_for_empty = QueryStatus::failed;
};

// The statuses an input may state (a front file's `status` line, a table's `status` column, a
// JSON record's "status"): every status but not-run, which is what a query without input gets.
// The message names the accepted words.
std::optional<std::string> stated_status_problem(std::string_view word, QueryStatus& status);

// One query's result as the writer takes it.
struct ImportedResult {
  std::uint64_t query = 0;  // 0-based index in the query set
  QueryStatus status = QueryStatus::solved;
  std::vector<double> costs;  // front_size·d values, vector after vector
  QueryStatistics statistics;
  bool status_stated = false;  // the input said the status (else it follows from the front)
  std::string statement = {};  // what the input said, where it said more than a status word
  // Where the result and each of its vectors came from, for messages on values the writer refuses:
  // "FILE", "FILE:LINE" or "FILE: JSON-POINTER".
  std::string source = {};
  std::vector<std::string> vector_sources = {};
};

// One front as text: one vector per line, values separated by blanks, commas or semicolons,
// optionally inside [ ]; blank lines and '#' comment lines skipped. A line `status WORD` states the
// query's status (stated_status_problem), one `exit_status N` a failed query's exit status; a
// stated status other than solved comes with no vector. An empty front without a stated status
// gets options.status_for_empty. Throws mosb::Error "FILE:LINE:COLUMN: message".
ImportedResult parse_front_text(std::string_view text, const std::string& display_name,
                                std::uint64_t query, const SolutionImportOptions& options);

// Every regular file of `directory`: the last run of digits of its name before the first '.' is
// the query id (id_base applies), e.g. `17.txt` or `query-17.front`. Sorted by query.
std::vector<ImportedResult> import_front_directory(const std::filesystem::path& directory,
                                                   const SolutionImportOptions& options);

// A table with a header line, tab- or comma-separated (tab when the header has one): a `query`
// column (the query id) and the cost columns, named after the view's objectives (`names`) unless
// options.columns picks them by position; one row per vector, rows of a query in any order. An
// optional `status` column states the query's status (rows of a query agree; a status other than
// solved has one row with empty cost fields) and an optional `exit_status` column a failed query's
// exit status (empty on other rows).
std::vector<ImportedResult> parse_solution_table(std::string_view text,
                                                 const std::string& display_name,
                                                 std::span<const std::string> names,
                                                 const SolutionImportOptions& options);

// A JSON array of records {"source", "target", "finish_info": {"solutions": [{"cost_until_now":
// [..]}, ..]}, "total_runtime(ms)"}. A record without solutions is a `disconnected` query. An
// optional "status" states the status (a status other than solved needs no finish_info and has no
// solutions), an optional "exit_status" a failed query's exit status.
std::vector<ImportedResult> parse_solver_json_log(std::string_view text,
                                                  const std::string& display_name,
                                                  const SolutionImportOptions& options);

// The per-query lines the example solvers print on standard output (examples/README.md): `start
// goal front_size seconds expansions`, one line per query in query order, query k's front in
// `<k>.txt` of their --fronts directory. Adds runtime_seconds and expanded to the results of
// import_front_directory (`results`, sorted by query) after checking each line: its endpoints are
// query k's (0-based vertex ids, as the examples print them), its front size is the number of
// vectors imported for query k, and query k has a front file; a front file without a line is
// refused too. An empty front file without a stated status whose line says front size 0 is
// `disconnected`: the solver finished the query and said so. Throws mosb::Error
// "FILE:LINE:COLUMN: message".
void apply_example_run_log(std::string_view text, const std::string& display_name,
                           const SolutionImportOptions& options,
                           std::vector<ImportedResult>& results);

// What to do with a front that is not a set of mutually non-dominated, distinct vectors.
enum class DominatedVectors {
  refuse,        // an error naming both vectors, their inputs and the query
  keep_optimal,  // keep the non-dominated subset (the first of equal vectors); record the drop
};

// Hands every result to the writer. A value the writer refuses (SolutionWriter::cost_problem: a
// fraction for an integer objective, a path sum above 2^53) is an error naming the input it came
// from (its vector_sources entry: FILE:LINE or FILE: JSON-POINTER), the query and the objective;
// any other refusal is prefixed with the result's source. A front holding a vector that another
// of its vectors weakly dominates or repeats (mosb::dominated_rows) is refused naming the query,
// both vectors and their inputs ("SOURCE: query Q: [dominated] vector V is dominated by W (at
// SOURCE2); ..."), unless `dominated` is keep_optimal: then only the non-dominated subset is kept
// (the first of equal vectors) and the writer records how many vectors were dropped and from how
// many queries (SolutionWriter::set_dropped_vectors), which is returned.
DroppedVectors set_imported_results(SolutionWriter& writer, std::span<const ImportedResult> results,
                                    DominatedVectors dominated = DominatedVectors::refuse);

}  // namespace mosb::converters
