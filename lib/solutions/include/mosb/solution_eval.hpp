// `mosb eval` over solution files (spec/EVALUATION.md §4): a solver's solution file against a
// reference solution file of the same instance, view and query set, query by query; and the
// options every comparison of solution files takes (eval, `solutions compare`, report).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "mosb/enum_names.hpp"
#include "mosb/eval.hpp"
#include "mosb/solution_file.hpp"

namespace mosb {

// Which runtime a comparison summarises (spec/SOLUTIONS.md §4): mosb's wall clock over the
// solver's process tree (`runtime_seconds`), or the solver's own figure
// (`reported_runtime_seconds`, format 1.5).
enum class RuntimeSource : std::uint8_t { wall, reported };
inline constexpr auto kRuntimeSourceNames = enum_names<RuntimeSource>({
    {RuntimeSource::wall, "wall"},
    {RuntimeSource::reported, "reported"},
});
std::string_view to_string(RuntimeSource source);  // kRuntimeSourceNames
constexpr Statistic runtime_statistic(RuntimeSource source) {
  return source == RuntimeSource::reported ? Statistic::reported_runtime_seconds
                                           : Statistic::runtime_seconds;
}
// What the solver's own runtime of a file measures: its profile's `runtime_clock` (metadata
// solution.solver.param.profile.runtime_clock: "wall" or "cpu"), else "wall" (the protocol line
// `mosb: runtime_seconds=` is the solver's wall clock, spec/RUN.md).
std::string reported_clock(const SolutionReader& file);
// The runtime a comparison summarises when the user chose none (spec/EVALUATION.md §4): `reported`
// when there is a file, every file records the solver's own runtime and every one's
// reported_clock is the same, else `wall` (so that solvers are never ranked by two different
// clocks unasked). `chosen`, when given, wins.
RuntimeSource choose_runtime(std::span<const SolutionReader* const> files,
                             std::optional<RuntimeSource> chosen = std::nullopt);

// The default relative tolerance of float objectives (spec/EVALUATION.md §2.1): the per-arc
// tolerance `solutions verify` allows a float path sum.
inline constexpr double kDefaultTolerance = 1e-9;

// How solution files are compared: by eval (compare_solvers, evaluate_solutions), by `solutions
// compare` (compare_fronts) and by report.
struct ComparisonOptions {
  EvalOptions eval;
  // Relative tolerance of floating-point objectives, in [0, 1): the values of one float objective
  // in the two fronts compared are grouped from the smallest, a group holding every value up to
  // (1 + tolerance) times its first, and each value is compared as its group's first
  // (spec/EVALUATION.md §2.1). 0: exact. Integer objectives are always compared exactly.
  double tolerance = kDefaultTolerance;
  // The runtimes summarised; nullopt: choose_runtime of the files compared.
  std::optional<RuntimeSource> runtime;
  double runtime_shift_seconds = 1;  // s of the shifted geometric mean
};

// Why a query the reference solved passes or fails at one requested ε: one answer per query and
// ε (spec/EVALUATION.md §4), in this order of precedence: the solver did not solve it; the solver
// claims exactness (solution.epsilon = 0) and returned vectors the reference dominates; its front
// does not cover the reference's at ε (at ε = 0: is not the same multiset); it does.
enum class QueryOutcome : std::uint8_t { not_solved, dominated, not_covered, covered };
inline constexpr auto kQueryOutcomeNames = enum_names<QueryOutcome>({
    {QueryOutcome::not_solved, "not_solved"},
    {QueryOutcome::dominated, "dominated"},
    {QueryOutcome::not_covered, "not_covered"},
    {QueryOutcome::covered, "covered"},
});
std::string_view to_string(QueryOutcome outcome);  // kQueryOutcomeNames

struct QueryEvaluation {
  std::uint64_t query = 0;
  QueryStatus reference_status = QueryStatus::not_run;
  QueryStatus solution_status = QueryStatus::not_run;
  // Set when both statuses are `solved`; otherwise the query fails at every ε.
  std::optional<FrontEvaluation> front;
  // The worst reference vector's values (objective order), when front->worst_reference is set.
  std::vector<double> worst_reference_values;
  // The solver claims exactness and returned vectors the reference strictly dominates.
  bool dominated = false;
  // Uncovered at some requested ε not below the solver's own (an ε-approximate solver promises
  // nothing finer), not solved, dominated, or solved where the reference found the goal
  // unreachable.
  bool failed = false;

  // The outcome at requested ε number k; nullopt when the reference did not solve the query.
  std::optional<QueryOutcome> outcome(std::size_t k) const;
};

struct SolutionEvaluation {
  std::vector<QueryEvaluation> queries;
  std::vector<std::uint64_t> covered_per_epsilon;  // queries covered, one per requested ε
  bool failed = false;
  // All objectives integer: achieved ε is the exact Ratio; otherwise only achieved_value.
  bool exact_arithmetic = false;
  // The solver's own ε (SolverInfo::epsilon), and whether it is 0: a vector the reference
  // dominates is then a bug.
  Ratio solver_epsilon;
  bool solver_claims_exact = true;
};

// Throws mosb::Error (ErrorCode::invalid_argument) naming both files and both values unless they
// share instance digest, objectives (names, in order), query set, query count and the header's n
// and m. A view is only a name for an objective list: files of two views with the same list
// compare. Either file may be
// the reference: the message names files, not roles.
void check_same_binding(const SolutionReader& reference, const SolutionReader& solution);

// Throws as check_same_binding (naming both files) unless they share the binding, and
// ErrorCode::invalid_argument for a tolerance outside [0, 1). Integer objectives are compared
// exactly, a view with any floating-point objective in double arithmetic, its float objectives
// within options.tolerance.
SolutionEvaluation evaluate_solutions(const SolutionReader& reference,
                                      const SolutionReader& solution,
                                      std::span<const Ratio> epsilons,
                                      const ComparisonOptions& options = {});

}  // namespace mosb
