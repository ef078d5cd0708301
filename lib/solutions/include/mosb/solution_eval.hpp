// `mosb eval` over solution files (spec/EVALUATION.md §4): a solver's solution file against a
// reference solution file of the same instance, view and query set, query by query.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "mosb/eval.hpp"
#include "mosb/solution_file.hpp"

namespace mosb {

struct QueryEvaluation {
  std::uint64_t query = 0;
  QueryStatus reference_status = QueryStatus::not_run;
  QueryStatus solution_status = QueryStatus::not_run;
  // Set when both statuses are `solved`; otherwise the query fails at every ε.
  std::optional<FrontEvaluation> front;
  // The worst reference vector's values (objective order), when front->worst_reference is set.
  std::vector<double> worst_reference_values;
  // Uncovered at some requested ε, not solved, or (from a solver claiming exactness,
  // metadata solution.epsilon = 0) vectors the reference strictly dominates.
  bool failed = false;
};

struct SolutionEvaluation {
  std::vector<QueryEvaluation> queries;
  std::vector<std::uint64_t> covered_per_epsilon;  // queries covered, one per requested ε
  bool failed = false;
  // All objectives integer: achieved ε is the exact Ratio; otherwise only achieved_value.
  bool exact_arithmetic = false;
  // The solver's own ε (SolverInfo::epsilon) is 0: a vector the reference dominates is a bug.
  bool solver_claims_exact = true;
};

// Throws mosb::Error (ErrorCode::invalid_argument) naming both files and both values unless they
// share instance digest, objectives (names, in order), query set, query count and the header's n
// and m. A view is only a name for an objective list: files of two views with the same list
// compare. Either file may be
// the reference: the message names files, not roles.
void check_same_binding(const SolutionReader& reference, const SolutionReader& solution);

// Throws as check_same_binding (naming both files) unless they share the binding. Integer
// objectives are compared exactly, a view with any floating-point objective in double arithmetic.
SolutionEvaluation evaluate_solutions(const SolutionReader& reference,
                                      const SolutionReader& solution,
                                      std::span<const Ratio> epsilons,
                                      const EvalOptions& options = {});

}  // namespace mosb
