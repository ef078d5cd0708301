#include "mosb/solver_comparison.hpp"

#include <algorithm>
#include <map>

#include "mosb/error.hpp"

namespace mosb {
namespace {

SolverSummary summarize_solver(const SolutionReader& solution, SolutionEvaluation evaluation,
                               std::size_t epsilon_count) {
  SolverSummary s;
  s.name = solver_name(solution);
  s.file = solution.display_name();
  const SolutionReader* const files[] = {&solution};
  s.own = summarize_completed(files);
  s.per_epsilon.assign(epsilon_count, {});
  std::vector<double> achieved, ratios;
  for (const auto& q : evaluation.queries) {
    if (q.reference_status == QueryStatus::solved && q.solution_status != QueryStatus::solved)
      ++s.not_solved;
    if (!q.front) continue;
    for (std::size_t k = 0; k < epsilon_count; ++k)
      ++(q.front->coverage[k].covered ? s.per_epsilon[k].covered : s.per_epsilon[k].not_covered);
    achieved.push_back(q.front->achieved_value);
    // A solved reference front is never empty (verify_payload), so the ratio is defined.
    ratios.push_back(static_cast<double>(q.front->solution_size) /
                     static_cast<double>(q.front->reference_size));
  }
  s.achieved_epsilon = distribution_of(std::move(achieved));
  s.size_ratio = distribution_of(std::move(ratios));
  s.evaluation = std::move(evaluation);
  return s;
}

using Rows = std::vector<std::vector<double>>;

// Query q's front as a sorted set of vectors (integer sums up to 2^53 are exact as doubles).
Rows sorted_rows(const SolutionReader& r, std::uint64_t q) {
  const std::uint64_t begin = r.front_begin(q), size = r.front_size(q);
  Rows rows(size, std::vector<double>(r.objective_count()));
  for (std::size_t i = 0; i < r.objective_count(); ++i)
    for (std::uint64_t k = 0; k < size; ++k) rows[k][i] = r.value_as_double(i, begin + k);
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

void compare_query(const SolutionReader& a, const SolutionReader& b, QueryAgreement& out) {
  if (out.a_status != QueryStatus::solved || out.b_status != QueryStatus::solved) {
    out.equal = out.a_status == out.b_status;
    return;
  }
  const Rows ra = sorted_rows(a, out.query), rb = sorted_rows(b, out.query);
  auto ia = ra.begin(), ib = rb.begin();
  while (ia != ra.end() && ib != rb.end() && *ia == *ib) ++ia, ++ib;
  if (ia == ra.end() && ib == rb.end()) {
    out.equal = true;
    return;
  }
  out.difference_in_a = ib == rb.end() || (ia != ra.end() && *ia < *ib);
  out.first_difference = out.difference_in_a ? *ia : *ib;
}

}  // namespace

SolverComparison compare_solvers(const SolutionReader& reference,
                                 std::span<const SolutionReader> solutions,
                                 std::span<const Ratio> epsilons,
                                 const ComparisonOptions& options) {
  if (solutions.empty())
    throw Error(ErrorCode::invalid_argument, "no solution file to compare with the reference");
  SolverComparison result;
  result.runtime_shift_seconds = options.runtime_shift_seconds;
  for (const auto& solution : solutions) {
    auto evaluation = evaluate_solutions(reference, solution, epsilons, options.eval);
    result.failed = result.failed || evaluation.failed;
    result.solvers.push_back(summarize_solver(solution, std::move(evaluation), epsilons.size()));
  }
  // Two files of one solver (two runs, two machines) keep apart in every table by their files.
  std::map<std::string, int> uses;
  for (const auto& s : result.solvers) ++uses[s.name];
  for (auto& s : result.solvers)
    if (uses[s.name] > 1) s.name += " (" + s.file + ")";
  for (std::uint64_t q = 0; q < reference.query_count(); ++q) {
    const bool all = std::all_of(solutions.begin(), solutions.end(), [q](const SolutionReader& s) {
      return is_completed(s.status(q));
    });
    if (all) result.common_queries.push_back(q);
  }
  for (std::size_t i = 0; i < solutions.size(); ++i) {
    std::vector<double> times;
    for (const auto q : result.common_queries)
      if (const auto t = solutions[i].runtime_seconds(q)) times.push_back(*t);
    result.solvers[i].runtime = distribution_of(std::move(times), options.runtime_shift_seconds);
  }
  return result;
}

FrontAgreement compare_fronts(const SolutionReader& a, const SolutionReader& b) {
  check_same_binding(a, b);
  FrontAgreement result;
  std::vector<double> ratios;
  for (std::uint64_t q = 0; q < a.query_count(); ++q) {
    QueryAgreement agreement;
    agreement.query = q;
    agreement.a_status = a.status(q);
    agreement.b_status = b.status(q);
    compare_query(a, b, agreement);
    const auto ta = a.runtime_seconds(q), tb = b.runtime_seconds(q);
    if (ta && tb && *ta > 0) {
      agreement.runtime_ratio = *tb / *ta;
      ratios.push_back(*agreement.runtime_ratio);
    }
    ++(agreement.equal ? result.equal : result.different);
    result.queries.push_back(std::move(agreement));
  }
  result.runtime_ratio = distribution_of(std::move(ratios));
  return result;
}

}  // namespace mosb
