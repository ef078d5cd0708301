// Several solvers' solution files against one reference (spec/EVALUATION.md §4), summarised as a
// paper's results section reports them, and the cross-validation of two solvers' fronts (§6).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mosb/solution_eval.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_summary.hpp"

namespace mosb {

// The queries the reference solved, by their outcome at one ε (QueryOutcome): covered,
// not_covered, dominated and SolverSummary::not_solved add up to them.
struct EpsilonOutcome {
  std::uint64_t covered = 0;      // both solved, the solver's front covers the reference's at ε
  std::uint64_t not_covered = 0;  // both solved, not covered, no dominated vector claimed exact
  // Both solved, the solver claims exactness and returned vectors the reference dominates (the
  // same count at every ε: such a query fails at each).
  std::uint64_t dominated = 0;
  // The queries both solved: every one is one of the three.
  std::uint64_t evaluated() const { return covered + not_covered + dominated; }
};

struct SolverSummary {
  std::string name;  // solver_name
  std::string file;
  SolutionEvaluation evaluation;
  // The solver's own file: its statuses, and its front sizes and runtimes over the queries it
  // completed (summarize_completed, as `solutions inspect` and `report` say them).
  CompletedSummary own;
  std::uint64_t not_solved = 0;  // the reference solved it, the solver did not
  // The solver returned a front where the reference found the goal unreachable (disconnected).
  std::uint64_t solved_unreachable = 0;
  std::vector<EpsilonOutcome> per_epsilon;
  // Over the queries both solved (the solver's achieved ε, as a double; |S|/|R|).
  std::optional<Distribution> achieved_epsilon, size_ratio;
  // Runtime (ComparisonOptions::runtime) over the common queries (SolverComparison::
  // common_queries) that carry one.
  std::optional<Distribution> runtime;
  // Whether the file has that runtime's column at all (a file without reported runtimes has no
  // runtime sample under RuntimeSource::reported, which is said, not shown as "none").
  bool runtime_recorded = false;
};

struct SolverComparison {
  std::vector<SolverSummary> solvers;
  // Queries that every solver completed (solved or disconnected): the only fair runtime sample.
  std::vector<std::uint64_t> common_queries;
  double runtime_shift_seconds = 1;
  RuntimeSource runtime = RuntimeSource::wall;  // which runtime `runtime` summarises
  double tolerance = kDefaultTolerance;         // ComparisonOptions::tolerance, as applied
  bool failed = false;  // some solver failed some query (SolutionEvaluation::failed)
};

// Every file must be bound as the reference is (check_same_binding, which names both files).
// Throws ErrorCode::invalid_argument for an empty `solutions` or a tolerance outside [0, 1).
SolverComparison compare_solvers(const SolutionReader& reference,
                                 std::span<const SolutionReader> solutions,
                                 std::span<const Ratio> epsilons,
                                 const ComparisonOptions& options = {});

// Two solvers' fronts query by query: the paper's cross-validation of two exact solvers.
struct QueryAgreement {
  std::uint64_t query = 0;
  QueryStatus a_status = QueryStatus::not_run, b_status = QueryStatus::not_run;
  // Both solved: the fronts are equal as sets of vectors (duplicates ignored; float objectives
  // within ComparisonOptions::tolerance). Both carry no front (any other pair of statuses): equal
  // when the statuses are.
  bool equal = false;
  // When both solved and the sets differ: the lexicographically smallest vector of the symmetric
  // difference, and whether it is in A's front (else B's).
  std::vector<double> first_difference;
  bool difference_in_a = false;
  // B's runtime / A's (ComparisonOptions::runtime), when both have one and A's > 0.
  std::optional<double> runtime_ratio;
};

struct FrontAgreement {
  std::vector<QueryAgreement> queries;
  std::uint64_t equal = 0, different = 0;
  std::optional<Distribution> runtime_ratio;    // over the queries that have one
  RuntimeSource runtime = RuntimeSource::wall;  // which runtime the ratios are of
  double tolerance = kDefaultTolerance;         // as applied
};

// Throws as check_same_binding (naming both files) unless A and B share instance, objectives and
// query set, and for a tolerance outside [0, 1). Uses options.tolerance and options.runtime.
// O(F log F) for F vectors in all.
FrontAgreement compare_fronts(const SolutionReader& a, const SolutionReader& b,
                              const ComparisonOptions& options = {});

}  // namespace mosb
