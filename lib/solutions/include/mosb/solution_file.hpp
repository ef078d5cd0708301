// Solution files (file kind 2, spec/SOLUTIONS.md): the fronts a solver (or a reference run) found
// for the queries of one query set of one instance, bound to that instance by its content digest
// and to one view (objective list).
//
// SolutionReader maps a file and hands out zero-copy, bounds-checked views like GraphReader. What
// open() checks, in time independent of the file size: the container (FORMAT.md §9 steps 1-7), the
// section kinds, types and row counts of SOLUTIONS.md §3, the ends of the offset columns, and the
// binding metadata. verify_payload() checks the payload (checksums, statuses, offsets, values);
// verify_against() (solution_verify.hpp) the fronts against the instance.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/container.hpp"
#include "mosb/enum_names.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/metadata.hpp"

namespace mosb {

class GraphReader;
struct View;

// Stored as u8 in the solution_status section.
enum class QueryStatus : std::uint8_t {
  solved = 0,        // the front is the solver's answer (exact when solution.epsilon is 0)
  timeout = 1,       // no answer within the time limit: empty front, no statistics
  memory_limit = 2,  // no answer within the memory limit: empty front, no statistics
  disconnected = 3,  // the goal is unreachable from the start: empty front, statistics allowed
  not_run = 4,       // the query was not attempted: empty front, no statistics
  // Since 1.3: the solver crashed, exited non-zero or printed something unreadable: empty front;
  // the only statistic it may carry is exit_status.
  failed = 5,
};
inline constexpr std::uint8_t kLastQueryStatus = 5;
// Every status in stored order, and its name (spec/SOLUTIONS.md §4): the solution files' text, the
// journal's, the JSON reports' keys and the command line's choices.
inline constexpr QueryStatus kQueryStatuses[] = {
    QueryStatus::solved,       QueryStatus::timeout, QueryStatus::memory_limit,
    QueryStatus::disconnected, QueryStatus::not_run, QueryStatus::failed};
inline constexpr auto kQueryStatusNames = enum_names<QueryStatus>({
    {QueryStatus::solved, "solved"},
    {QueryStatus::timeout, "timeout"},
    {QueryStatus::memory_limit, "memory-limit"},
    {QueryStatus::disconnected, "disconnected"},
    {QueryStatus::not_run, "not-run"},
    {QueryStatus::failed, "failed"},
});
std::string_view to_string(QueryStatus status);  // kQueryStatusNames
std::optional<QueryStatus> parse_query_status(std::string_view text);

// Solved or disconnected: the search ran to its end, and what it found (a front, or that there is
// none) is its answer. Front sizes and runtimes are summarised over completed queries (the
// paper's Table 1; spec/EVALUATION.md §4).
constexpr bool is_completed(QueryStatus status) {
  return status == QueryStatus::solved || status == QueryStatus::disconnected;
}

// Queries per status, indexed by the status.
class StatusCounts {
 public:
  constexpr std::uint64_t& operator[](QueryStatus s) {
    return counts_[static_cast<std::size_t>(s)];
  }
  constexpr std::uint64_t operator[](QueryStatus s) const {
    return counts_[static_cast<std::size_t>(s)];
  }
  constexpr std::uint64_t total() const {
    std::uint64_t sum = 0;
    for (const auto count : counts_) sum += count;
    return sum;
  }
  constexpr std::uint64_t completed() const {
    std::uint64_t sum = 0;
    for (std::size_t s = 0; s < counts_.size(); ++s)
      if (is_completed(static_cast<QueryStatus>(s))) sum += counts_[s];
    return sum;
  }
  constexpr StatusCounts& operator+=(const StatusCounts& other) {
    for (std::size_t s = 0; s < counts_.size(); ++s) counts_[s] += other.counts_[s];
    return *this;
  }
  constexpr bool operator==(const StatusCounts&) const = default;

 private:
  std::array<std::uint64_t, kLastQueryStatus + 1> counts_{};
};

// The optional per-query statistics; each is its own solution_statistics section, named as here.
enum class Statistic : std::uint8_t {
  runtime_seconds,
  expanded,
  generated,
  peak_memory_bytes,
  exit_status,  // since 1.3, failed queries only: the exit code, or 128 + N for signal N
  // Since 1.5: the solver's own measurement of its runtime (its search, where a solver that loads
  // text per query reports the search alone), beside runtime_seconds (mosb's wall clock).
  reported_runtime_seconds,
};
inline constexpr Statistic kStatistics[] = {
    Statistic::runtime_seconds,   Statistic::expanded,    Statistic::generated,
    Statistic::peak_memory_bytes, Statistic::exit_status, Statistic::reported_runtime_seconds};
inline constexpr std::size_t kStatisticCount = std::size(kStatistics);
// Each statistic's section name.
inline constexpr auto kStatisticNames = enum_names<Statistic>({
    {Statistic::runtime_seconds, "runtime_seconds"},
    {Statistic::expanded, "expanded"},
    {Statistic::generated, "generated"},
    {Statistic::peak_memory_bytes, "peak_memory_bytes"},
    {Statistic::exit_status, "exit_status"},
    {Statistic::reported_runtime_seconds, format::kReportedRuntimeStatistic},
});
std::string_view to_string(Statistic s);  // kStatisticNames
// The runtimes are f64 seconds (absent: NaN); the counters are u64 (absent: kAbsentCount).
constexpr bool is_seconds(Statistic s) {
  return s == Statistic::runtime_seconds || s == Statistic::reported_runtime_seconds;
}
inline constexpr std::uint64_t kAbsentCount = std::numeric_limits<std::uint64_t>::max();
// The largest integer path sum a solution file stores: every integer up to 2^53 is exact as a
// double, which is how the importers parse costs and how verify, eval, plot and export read them.
inline constexpr std::uint64_t kMaxIntegerSum = std::uint64_t{1} << 53;

// Per-query statistics as the writer takes them; nullopt means absent.
struct QueryStatistics {
  std::optional<double> runtime_seconds;
  std::optional<std::uint64_t> expanded;
  std::optional<std::uint64_t> generated;
  std::optional<std::uint64_t> peak_memory_bytes;
  std::optional<std::uint64_t> exit_status =
      std::nullopt;  // default: brace lists of four stay valid
  std::optional<double> reported_runtime_seconds = std::nullopt;
};

// Who produced the fronts (metadata `solution.solver.*`, `solution.epsilon`, `solution.machine`).
struct SolverInfo {
  std::string name;
  std::string version;
  std::map<std::string, std::string> parameters;  // keys from [A-Za-z0-9_.+-]
  std::string epsilon = "0";                      // decimal text; "0" = exact
  std::string machine;                            // free-text machine notes
};

// What `solutions import --nondominated` left out of the file (metadata
// `solution.import.dropped_vectors` and `solution.import.dropped_queries`, spec/SOLUTIONS.md §2):
// input vectors that another vector of the same query's front weakly dominated or repeated, and
// the number of queries that had any.
struct DroppedVectors {
  std::uint64_t vectors = 0, queries = 0;
  bool operator==(const DroppedVectors&) const = default;
};

class SolutionReader : public ContainerReader {
 public:
  // Maps the file, or decodes it into memory when it is packed (SOLUTIONS.md §1; every section's
  // checksum checked, within the memory the system reports available), and checks the container
  // and the sections' shapes and binding keys.
  static SolutionReader open(const std::filesystem::path& path);
  // Opens, then requires the file to belong to `instance` (check_bound_to).
  static SolutionReader open(const std::filesystem::path& path, const GraphReader& instance);
  // Opens, then checks the payload (verify_payload()): what every command that reads the fronts
  // uses, so one flipped byte is an ErrorCode::damaged error "FILE: file is damaged: PROBLEM; run
  // mosb verify", never a number or a figure made of corrupt data.
  static SolutionReader open_verified(const std::filesystem::path& path);
  // The same over bytes the caller keeps alive (8-byte aligned); packed bytes are decoded into
  // memory the reader owns, within `max_memory` bytes (0: the memory available).
  static SolutionReader from_memory(std::span<const std::byte> bytes, std::string display_name,
                                    std::uint64_t max_memory = 0);

  // Throws ErrorCode::invalid_argument "FILE: solutions of instance DIGEST, not of INSTANCE
  // (DIGEST)" unless the file's instance digest is the instance's; also checks the header's n and m
  // against the instance's, that the view (when the file names one) exists with the file's
  // objectives, each front_cost column's objective with its type, and the query set with the
  // file's query count.
  void check_bound_to(const GraphReader& instance) const;
  // The instance's objective index of each front_cost column, in column order: the view's
  // objectives (checked by name), or for a file without a view each column's objective by name.
  std::vector<std::size_t> instance_objectives(const GraphReader& instance) const;

  const Metadata& metadata() const { return metadata_; }

  const std::string& instance_digest() const { return instance_digest_; }
  // The view the fronts were written for; empty in a 1.4 file bound to its objectives alone.
  const std::string& view_name() const { return view_; }
  const std::string& query_set() const { return query_set_; }
  SolverInfo solver() const;
  // nullopt when the file records no drop (it was not imported with --nondominated); throws
  // mosb::Error when the keys are not both unsigned decimal integers.
  std::optional<DroppedVectors> dropped_vectors() const;

  // Whether the front_cost columns hold path sums in format::path_sum_type (format 1.3 on), or,
  // in a 1.1/1.2 file, each objective in its arc cost type. Readers need not care: every value
  // reads through visit_column / value_as_double whatever its stored type, i.e. widened.
  bool stores_path_sums() const { return header_.version_minor >= format::kSolutionSumsMinor; }
  // The view's objectives in order: names and stored types of the front_cost columns.
  std::size_t objective_count() const { return cost_indices_.size(); }
  const std::string& objective_name(std::size_t i) const { return objective(i).name; }
  format::ElementType objective_type(std::size_t i) const { return objective(i).type; }
  const Section& objective(std::size_t i) const;

  std::uint64_t query_count() const { return query_count_; }
  std::uint64_t vector_count() const { return vector_count_; }  // F: all fronts together
  QueryStatus status(std::uint64_t q) const;  // throws on a stored value outside the enum
  std::span<const std::uint64_t> front_offsets() const;
  // The rows [first, first + size) of the cost columns that hold query q's front.
  std::uint64_t front_begin(std::uint64_t q) const;
  std::uint64_t front_size(std::uint64_t q) const;

  // A whole cost column (F values) in its stored type; asking for another type is an error.
  template <class T>
  std::span<const T> column(std::size_t objective_index) const {
    return values<T>(objective(objective_index));
  }
  // Query q's values of one objective in its stored type.
  template <class T>
  std::span<const T> front(std::size_t objective_index, std::uint64_t q) const {
    return column<T>(objective_index).subspan(front_begin(q), front_size(q));
  }
  // Calls f(std::span<const T>) with the whole column i in its stored type T (unsigned or float)
  // and returns what f returns (one type for every T), as GraphReader::visit_cost.
  template <class F>
  decltype(auto) visit_column(std::size_t i, F&& f) const;
  // Value of objective i for front vector `row` (0 <= row < F), converted to double.
  double value_as_double(std::size_t objective_index, std::uint64_t row) const;

  bool has_statistic(Statistic s) const { return statistic_index(s) != SIZE_MAX; }
  // nullopt when the file has no such column or the query's entry is absent.
  std::optional<double> runtime_seconds(std::uint64_t q) const;
  std::optional<double> reported_runtime_seconds(std::uint64_t q) const;
  // A runtime statistic (is_seconds), or nullopt.
  std::optional<double> seconds_statistic(Statistic s, std::uint64_t q) const;
  // A counter statistic (not is_seconds), or nullopt.
  std::optional<std::uint64_t> count_statistic(Statistic s, std::uint64_t q) const;
  // Any statistic's value as a double, or nullopt.
  std::optional<double> statistic_as_double(Statistic s, std::uint64_t q) const;
  QueryStatistics statistics(std::uint64_t q) const;

  bool has_paths() const { return path_offsets_index_ != SIZE_MAX; }
  // The vertex sequence of front vector `row`; empty when the file has no paths.
  std::span<const std::uint32_t> path(std::uint64_t row) const;

  // Payload checks of SOLUTIONS.md §5 that need no instance: section checksums, statuses in range,
  // offsets non-decreasing, fronts empty where the status says so, statistics absent where the
  // status says so, float costs and runtimes finite and >= 0. The first problem, or nullopt.
  std::optional<std::string> verify_payload() const;

 private:
  SolutionReader() = default;
  void validate();
  std::size_t statistic_index(Statistic s) const;

  Metadata metadata_;
  std::string instance_digest_, view_, query_set_;
  std::uint64_t query_count_ = 0, vector_count_ = 0;
  std::size_t status_index_ = SIZE_MAX, front_offsets_index_ = SIZE_MAX;
  std::size_t path_offsets_index_ = SIZE_MAX, path_vertices_index_ = SIZE_MAX;
  std::vector<std::size_t> cost_indices_;
  std::size_t statistic_indices_[kStatisticCount] = {SIZE_MAX, SIZE_MAX, SIZE_MAX,
                                                     SIZE_MAX, SIZE_MAX, SIZE_MAX};
};

template <class F>
decltype(auto) SolutionReader::visit_column(std::size_t i, F&& f) const {
  return visit_cost_values(objective(i), std::forward<F>(f));
}

// Collects fronts query by query and writes a solution file (format 1.3) for one view and query set
// of an instance. Costs arrive as doubles, path sums, and are stored in format::path_sum_type of
// each objective's arc type (u64 for unsigned, f64 for float objectives); an integer objective
// refuses a non-integral, negative or larger than kMaxIntegerSum value.
// SolutionReader::open_verified of every path, in order, on up to `threads` threads (0: as many as
// the hardware runs): a packed file's decoding is most of an open. A failure is thrown as a loop
// would throw it, the first in path order.
std::vector<SolutionReader> open_verified_all(std::span<const std::filesystem::path> paths,
                                              unsigned threads = 0);

class SolutionWriter {
 public:
  // `query_set` empty: the view's query set (an error when the view names none).
  SolutionWriter(const GraphReader& instance, std::string_view view_name,
                 std::string_view query_set = {});
  // A selection as mosb::select_view resolves one: with an empty name the file records no view and
  // is bound to its objectives (format 1.4, spec/SOLUTIONS.md §2); a query set is required.
  SolutionWriter(const GraphReader& instance, const View& selection);
  // The binding of an existing file (instance digest, n and m, view, objective names and types,
  // query set and its size), for tools that join solution files without their instance.
  explicit SolutionWriter(const SolutionReader& like);
  ~SolutionWriter();
  SolutionWriter(const SolutionWriter&) = delete;
  SolutionWriter& operator=(const SolutionWriter&) = delete;

  void set_solver(SolverInfo info);
  // Records what an import left out (metadata solution.import.*); nullopt (the default): nothing.
  void set_dropped_vectors(std::optional<DroppedVectors> dropped);
  // The `source.tool` stamp (default "mosb VERSION"); golden files pin it.
  void set_source_tool(std::string tool);
  std::size_t objective_count() const;
  std::uint64_t query_count() const;  // Q: the query set's size
  const std::vector<std::string>& objective_names() const;

  // Why `value` cannot be objective i's path sum (negative, not finite, a fraction or above
  // kMaxIntegerSum for an integer objective), or nullopt. set_query refuses such a value with this
  // message; importers call it to name the input line of the value.
  std::optional<std::string> cost_problem(std::size_t objective, double value) const;

  // Sets query q's result (any order; a query never set is written as not_run). `costs` holds
  // front_size·d values row-major (vector after vector). `paths`, when given, holds one vertex
  // sequence per vector. Throws mosb::Error (ErrorCode::invalid_argument) naming the query on a
  // value cost_problem refuses, a front for a status that has none, statistics for a timeout,
  // memory-limit or not-run query, or a failed query with a statistic other than exit_status.
  void set_query(std::uint64_t q, QueryStatus status, std::span<const double> costs,
                 const QueryStatistics& statistics = {},
                 std::span<const std::vector<std::uint32_t>> paths = {});
  // What set_query would refuse, without the query's name, or nullopt: `mosb run` records such a
  // query failed (a solver's bad statistic fails its query, not the run) and refuses a journal
  // record with one.
  std::optional<std::string> query_problem(
      std::uint64_t q, QueryStatus status, std::span<const double> costs,
      const QueryStatistics& statistics = {},
      std::span<const std::vector<std::uint32_t>> paths = {}) const;

  // Writes the file atomically (mosb::FileWriter). Paths are written when every non-empty front
  // came with them; a file mixing fronts with and without paths is refused.
  void write(const std::filesystem::path& target) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace mosb
