#include "mosb/solver_comparison.hpp"

#include <algorithm>
#include <map>

#include "mosb/error.hpp"
#include "tolerance.hpp"

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
    if (q.reference_status == QueryStatus::disconnected && q.solution_status == QueryStatus::solved)
      ++s.solved_unreachable;
    if (!q.front) continue;
    for (std::size_t k = 0; k < epsilon_count; ++k) {
      auto& counts = s.per_epsilon[k];
      const auto outcome = q.outcome(k);
      ++(outcome == QueryOutcome::covered       ? counts.covered
         : outcome == QueryOutcome::not_covered ? counts.not_covered
                                                : counts.dominated);
    }
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

// Query q's front, row-major (integer sums up to 2^53 are exact as doubles).
std::vector<double> front_rows(const SolutionReader& r, std::uint64_t q) {
  const std::size_t d = r.objective_count();
  const std::uint64_t begin = r.front_begin(q), size = r.front_size(q);
  std::vector<double> rows(size * d);
  for (std::size_t i = 0; i < d; ++i)
    for (std::uint64_t k = 0; k < size; ++k) rows[k * d + i] = r.value_as_double(i, begin + k);
  return rows;
}

// The vectors of a front as compared (`keys`, float objectives within the tolerance) and as
// stored (`values`), sorted by key, one per distinct key (the first stored in that order).
struct ComparedFront {
  std::vector<double> keys, values;
  std::vector<std::size_t> order;
  std::size_t d;
  const double* key(std::size_t k) const { return keys.data() + order[k] * d; }
  const double* value(std::size_t k) const { return values.data() + order[k] * d; }
};

ComparedFront compared(std::vector<double> keys, std::vector<double> values, std::size_t d) {
  ComparedFront f{std::move(keys), std::move(values), {}, d};
  f.order.resize(d == 0 ? 0 : f.keys.size() / d);
  for (std::size_t k = 0; k < f.order.size(); ++k) f.order[k] = k;
  const auto less = [&](std::size_t a, std::size_t b) {
    const double *x = f.keys.data() + a * d, *y = f.keys.data() + b * d;
    if (std::lexicographical_compare(x, x + d, y, y + d)) return true;
    if (std::lexicographical_compare(y, y + d, x, x + d)) return false;
    const double *u = f.values.data() + a * d, *v = f.values.data() + b * d;
    return std::lexicographical_compare(u, u + d, v, v + d);
  };
  std::sort(f.order.begin(), f.order.end(), less);
  const auto same_key = [&](std::size_t a, std::size_t b) {
    return std::equal(f.keys.data() + a * d, f.keys.data() + (a + 1) * d, f.keys.data() + b * d);
  };
  f.order.erase(std::unique(f.order.begin(), f.order.end(), same_key), f.order.end());
  return f;
}

void compare_query(const SolutionReader& a, const SolutionReader& b,
                   const std::vector<bool>& is_float, double tolerance, QueryAgreement& out) {
  if (out.a_status != QueryStatus::solved || out.b_status != QueryStatus::solved) {
    out.equal = out.a_status == out.b_status;
    return;
  }
  const std::size_t d = a.objective_count();
  auto rows_a = front_rows(a, out.query), rows_b = front_rows(b, out.query);
  auto keys_a = rows_a, keys_b = rows_b;
  solutions_internal::snap_within_tolerance(keys_a, keys_b, d, is_float, tolerance);
  const auto fa = compared(std::move(keys_a), std::move(rows_a), d);
  const auto fb = compared(std::move(keys_b), std::move(rows_b), d);
  std::size_t ia = 0, ib = 0;
  while (ia < fa.order.size() && ib < fb.order.size() &&
         std::equal(fa.key(ia), fa.key(ia) + d, fb.key(ib)))
    ++ia, ++ib;
  if (ia == fa.order.size() && ib == fb.order.size()) {
    out.equal = true;
    return;
  }
  out.difference_in_a =
      ib == fb.order.size() ||
      (ia < fa.order.size() &&
       std::lexicographical_compare(fa.key(ia), fa.key(ia) + d, fb.key(ib), fb.key(ib) + d));
  const double* v = out.difference_in_a ? fa.value(ia) : fb.value(ib);
  out.first_difference.assign(v, v + d);
}

}  // namespace

SolverComparison compare_solvers(const SolutionReader& reference,
                                 std::span<const SolutionReader> solutions,
                                 std::span<const Ratio> epsilons,
                                 const ComparisonOptions& options) {
  if (solutions.empty())
    throw Error(ErrorCode::invalid_argument, "no solution file to compare with the reference");
  solutions_internal::check_tolerance(options.tolerance);
  std::vector<const SolutionReader*> files;
  for (const auto& s : solutions) files.push_back(&s);
  SolverComparison result;
  result.runtime_shift_seconds = options.runtime_shift_seconds;
  result.runtime = choose_runtime(files, options.runtime);
  result.tolerance = options.tolerance;
  for (const auto& solution : solutions) {
    auto evaluation = evaluate_solutions(reference, solution, epsilons, options);
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
  const auto statistic = runtime_statistic(result.runtime);
  for (std::size_t i = 0; i < solutions.size(); ++i) {
    std::vector<double> times;
    for (const auto q : result.common_queries)
      if (const auto t = solutions[i].statistic_as_double(statistic, q)) times.push_back(*t);
    result.solvers[i].runtime = distribution_of(std::move(times), options.runtime_shift_seconds);
    result.solvers[i].runtime_recorded = solutions[i].has_statistic(statistic);
  }
  return result;
}

FrontAgreement compare_fronts(const SolutionReader& a, const SolutionReader& b,
                              const ComparisonOptions& options) {
  check_same_binding(a, b);
  solutions_internal::check_tolerance(options.tolerance);
  const auto is_float = solutions_internal::float_objectives(a, b);
  const SolutionReader* const files[] = {&a, &b};
  FrontAgreement result;
  result.runtime = choose_runtime(files, options.runtime);
  const auto statistic = runtime_statistic(result.runtime);
  result.tolerance = options.tolerance;
  std::vector<double> ratios;
  for (std::uint64_t q = 0; q < a.query_count(); ++q) {
    QueryAgreement agreement;
    agreement.query = q;
    agreement.a_status = a.status(q);
    agreement.b_status = b.status(q);
    compare_query(a, b, is_float, options.tolerance, agreement);
    const auto ta = a.statistic_as_double(statistic, q), tb = b.statistic_as_double(statistic, q);
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
