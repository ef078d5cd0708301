// `mosb solutions merge` (spec/RUN.md §7): solution files of one run split into parts, typically
// the shards of `mosb run --shard i/N`, joined into one. The inputs must be bound alike (instance,
// objective list and view, query set), come from the same solver with the same settings (metadata
// `solution.solver.*` and `solution.epsilon`: everything but where and how each part ran), and be
// disjoint: a query that is not `not-run` in one input is `not-run` in every other. Queries that
// are `not-run` everywhere are missing.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/solution_file.hpp"

namespace mosb {

// Shard i of N (1 <= i <= N): query k of the set belongs to shard (k mod N) + 1 (spec/RUN.md §7).
struct Shard {
  std::uint64_t index = 1, count = 1;
  bool contains(std::uint64_t query) const { return query % count == index - 1; }
  // The number of queries of a set of `queries` this shard holds.
  std::uint64_t size(std::uint64_t queries) const {
    return queries / count + (index - 1 < queries % count ? 1 : 0);
  }
  std::string text() const { return std::to_string(index) + "/" + std::to_string(count); }
};
// "i/N" with 1 <= i <= N (decimal digits only); nullopt when malformed.
std::optional<Shard> parse_shard(std::string_view text);

// Inputs that do not belong together (another binding, solver or setting; a query in two inputs;
// a shard twice). The message names the file and what differs.
class SolutionMergeConflict : public Error {
 public:
  explicit SolutionMergeConflict(const std::string& what)
      : Error(ErrorCode::invalid_argument, what) {}
};

// The metadata parameters (solution.solver.param.*) that may differ between the parts: where and
// how each part ran, not what ran. The merged file keeps a value all parts share, else every
// distinct value, sorted, joined by " | " (as it does for solution.machine).
std::span<const std::string_view> merge_lenient_parameters();

struct MergedInput {
  std::filesystem::path file;
  std::optional<std::uint64_t> shard;  // i of run.shard "i/N"
  std::uint64_t queries = 0;           // the queries it contributes (not not-run)
};

class SolutionMerge {
 public:
  // Opens and checks every input (open_verified: damaged files are refused), in the order given;
  // throws SolutionMergeConflict naming the first input that does not fit the ones before it.
  explicit SolutionMerge(std::span<const std::filesystem::path> inputs);
  ~SolutionMerge();
  SolutionMerge(SolutionMerge&&) noexcept;
  SolutionMerge(const SolutionMerge&) = delete;
  SolutionMerge& operator=(const SolutionMerge&) = delete;

  std::uint64_t query_count() const;  // Q of the query set
  const std::string& query_set() const;
  const std::vector<MergedInput>& inputs() const;
  // N when the inputs are shards of `mosb run --shard i/N` (all of them carry run.shard), else
  // nullopt; and then the shard indices 1..N no input is.
  std::optional<std::uint64_t> shard_count() const;
  std::vector<std::uint64_t> absent_shards() const;
  // Queries not-run in every input, ascending.
  const std::vector<std::uint64_t>& missing() const;
  // The merged file's statuses (missing queries are not_run).
  StatusCounts status_counts() const;

  // Writes the merged file atomically. Its bytes depend on the inputs' contents only, not on their
  // order or names.
  void write(const std::filesystem::path& output) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace mosb
