// Reference fronts cross-validated from several exact solvers (spec/EVALUATION.md §7, `mosb
// solutions reference`): per query the front the solvers that completed it agree on (float
// objectives within the comparison tolerance of `solutions compare`), who agreed, and the
// disagreements, written as one solution file whose metadata records who agreed on what.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mosb/enum_names.hpp"
#include "mosb/solution_eval.hpp"
#include "mosb/solution_file.hpp"

namespace mosb {

// How a query's reference was decided.
enum class ReferenceKind {
  agreed,        // two or more solvers completed it and all agree: their front
  single,        // exactly one solver completed it: its front, marked as not cross-validated
  disagreement,  // the solvers that completed it disagree: left out (not-run)
  preferred,     // they disagree and ReferenceOptions::prefer completed it: its front
  unsolved,      // no solver completed it: timeout, memory-limit or not-run (see cross_validate)
};
inline constexpr auto kReferenceKindNames = enum_names<ReferenceKind>({
    {ReferenceKind::agreed, "agreed"},
    {ReferenceKind::single, "single"},
    {ReferenceKind::disagreement, "disagreement"},
    {ReferenceKind::preferred, "preferred"},
    {ReferenceKind::unsolved, "unsolved"},
});
std::string_view to_string(ReferenceKind kind);  // kReferenceKindNames

struct ReferenceOptions {
  // The exact solvers, by solver_name, in the order given (the first that completed a query is
  // the one the others are compared with).
  std::vector<std::string> solvers;
  std::optional<std::string> prefer;  // keeps its front where the solvers disagree
  double tolerance = kDefaultTolerance;
};

struct ReferenceQuery {
  std::uint64_t query = 0;
  ReferenceKind kind = ReferenceKind::unsolved;
  QueryStatus status = QueryStatus::not_run;  // the reference's
  // The solver whose front the reference holds (agreed: the first that completed it); empty when
  // the reference holds none.
  std::string source;
  std::vector<std::string> agreed;  // agreed, single, preferred: who gave this front (in order)
  // disagreement and preferred: the first solver that completed the query, the first that
  // disagrees with it, and the lexicographically smallest vector of their fronts' symmetric
  // difference (empty when their statuses differ: solved against disconnected), in `in_first`'s.
  std::string first, differing;
  std::vector<double> first_difference;
  bool difference_in_first = false;
};

struct CrossValidation {
  std::vector<std::string> solvers;  // as given
  std::vector<ReferenceQuery> queries;
  std::uint64_t count(ReferenceKind kind) const;
};

// `files` holds at most one file per solver of options.solvers (solver_name), every one of one
// binding (check_same_binding). A solver without a file counts as not-run on every query. A query
// no solver completed is `timeout` when every solver that ran it (not-run ones left out) timed out
// or hit the memory limit and one timed out, `memory-limit` when all hit the memory limit, else
// not-run. Throws
// mosb::Error (invalid_argument) for no solver, a solver named twice or with a ',', a file of a
// solver not named or two of one solver, no file at all, `prefer` not among the solvers, or a
// tolerance outside [0, 1).
CrossValidation cross_validate(std::span<const SolutionReader* const> files,
                               const ReferenceOptions& options);

// The reference as a solution file of the files' binding: each query's status and the front of its
// `source` (no paths), solver name "reference", exact (ε 0); the statistics (runtimes, expanded,
// generated, peak memory) of the first solver named, on the queries it completed with the
// reference's status, and no others; and the metadata `solution.solver.param.solvers` (the names,
// comma-separated), `.param.statistics` (the first solver's name, when it has a file),
// `.param.prefer` (when given) and
// per kind K other than unsolved `.param.K` (the queries, as ranges "0-4,7"), per solver i
// `.param.agreed.<i>` (the queries whose front it gave). Written atomically.
void write_reference(std::span<const SolutionReader* const> files,
                     const CrossValidation& validation, const ReferenceOptions& options,
                     const std::filesystem::path& target);

// The files of one binding (instance, view, query set), indices into the files given, and the
// reference's file name: the base name of the group's first file.
struct ReferenceGroup {
  std::vector<std::size_t> files;
  std::string name;
};
// The files of the named solvers (solver_name; others are left out) grouped by binding, in the
// order of their first file. Throws mosb::Error (invalid_argument) when two groups would have one
// name, for a named solver without a file, and for a file of a named solver that claims ε > 0.
std::vector<ReferenceGroup> reference_groups(std::span<const SolutionReader> files,
                                             const ReferenceOptions& options);
// Throws mosb::Error (invalid_argument, naming it) when the reference of a group, written into
// `directory`, would replace one of `files`: a reference never overwrites its inputs.
void check_reference_outputs(std::span<const SolutionReader> files,
                             std::span<const ReferenceGroup> groups,
                             const std::filesystem::path& directory);

// "0-4,7,9-12": ascending distinct numbers as ranges; "" for none.
std::string query_ranges(std::span<const std::uint64_t> queries);

}  // namespace mosb
