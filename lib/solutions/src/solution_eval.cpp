#include "mosb/solution_eval.hpp"

#include <algorithm>
#include <type_traits>

#include "mosb/error.hpp"
#include "tolerance.hpp"

namespace mosb {
namespace {

// Query q's front, row-major, in T (uint64_t for integer views, double otherwise).
template <class T>
std::vector<T> gather(const SolutionReader& r, std::uint64_t q) {
  const std::size_t d = r.objective_count();
  const std::uint64_t begin = r.front_begin(q), size = r.front_size(q);
  std::vector<T> rows(size * d);
  for (std::size_t i = 0; i < d; ++i) {
    r.visit_column(i, [&](auto column) {
      for (std::uint64_t k = 0; k < size; ++k) rows[k * d + i] = static_cast<T>(column[begin + k]);
    });
  }
  return rows;
}

// Query q's evaluation when both files solved it.
void evaluate_front_of(const SolutionReader& reference, const SolutionReader& solution,
                       std::span<const Ratio> epsilons, const ComparisonOptions& options,
                       const std::vector<bool>& is_float, QueryEvaluation& e) {
  const std::size_t d = reference.objective_count();
  const auto q = e.query;
  if (std::find(is_float.begin(), is_float.end(), true) == is_float.end()) {
    const auto s = gather<std::uint64_t>(solution, q), r = gather<std::uint64_t>(reference, q);
    e.front = evaluate_front(FrontView<std::uint64_t>{s, d}, FrontView<std::uint64_t>{r, d},
                             epsilons, options.eval);
  } else {
    auto s = gather<double>(solution, q), r = gather<double>(reference, q);
    solutions_internal::snap_within_tolerance(s, r, d, is_float, options.tolerance);
    e.front =
        evaluate_front(FrontView<double>{s, d}, FrontView<double>{r, d}, epsilons, options.eval);
  }
  if (e.front->worst_reference) {
    const std::uint64_t row = reference.front_begin(q) + *e.front->worst_reference;
    for (std::size_t i = 0; i < d; ++i)
      e.worst_reference_values.push_back(reference.value_as_double(i, row));
  }
}

}  // namespace

std::string_view to_string(RuntimeSource source) {
  return kRuntimeSourceNames.name(source);
}

std::string reported_clock(const SolutionReader& file) {
  const auto info = file.solver();
  const auto clock = info.parameters.find("profile.runtime_clock");
  return clock == info.parameters.end() ? "wall" : clock->second;
}

RuntimeSource choose_runtime(std::span<const SolutionReader* const> files,
                             std::optional<RuntimeSource> chosen) {
  if (chosen) return *chosen;
  if (files.empty()) return RuntimeSource::wall;
  const auto clock = reported_clock(*files.front());
  const bool one_clock = std::all_of(files.begin(), files.end(), [&](const SolutionReader* f) {
    return f->has_statistic(Statistic::reported_runtime_seconds) && reported_clock(*f) == clock;
  });
  return one_clock ? RuntimeSource::reported : RuntimeSource::wall;
}

std::string_view to_string(QueryOutcome outcome) {
  return kQueryOutcomeNames.name(outcome);
}

std::optional<QueryOutcome> QueryEvaluation::outcome(std::size_t k) const {
  if (reference_status != QueryStatus::solved) return std::nullopt;
  if (!front) return QueryOutcome::not_solved;
  if (dominated) return QueryOutcome::dominated;
  return front->coverage.at(k).covered ? QueryOutcome::covered : QueryOutcome::not_covered;
}

void check_same_binding(const SolutionReader& ref, const SolutionReader& sol) {
  const auto mismatch = [&](const std::string& what, const std::string& a, const std::string& b) {
    throw Error(ErrorCode::invalid_argument, ref.display_name() + " has " + what + " " + a + ", " +
                                                 sol.display_name() + " has " + b);
  };
  if (ref.instance_digest() != sol.instance_digest())
    mismatch("instance digest", ref.instance_digest(), sol.instance_digest());
  // The binding is (digest, objective list, query set): a view is only a name for a list.
  const auto objectives = [](const SolutionReader& r) {
    std::string names;
    for (std::size_t i = 0; i < r.objective_count(); ++i)
      names += (i ? "," : "") + r.objective_name(i);
    return names;
  };
  if (objectives(ref) != objectives(sol)) mismatch("objectives", objectives(ref), objectives(sol));
  if (ref.query_set() != sol.query_set()) mismatch("query set", ref.query_set(), sol.query_set());
  if (ref.query_count() != sol.query_count())
    mismatch("query count", std::to_string(ref.query_count()), std::to_string(sol.query_count()));
  // The same digest with other header counts: one file's n or m is not its instance's.
  const auto counts = [](const SolutionReader& r) {
    return "n = " + std::to_string(r.header().vertex_count) +
           ", m = " + std::to_string(r.header().arc_count);
  };
  if (counts(ref) != counts(sol)) mismatch("header", counts(ref), counts(sol));
}

SolutionEvaluation evaluate_solutions(const SolutionReader& reference,
                                      const SolutionReader& solution,
                                      std::span<const Ratio> epsilons,
                                      const ComparisonOptions& options) {
  check_same_binding(reference, solution);
  solutions_internal::check_tolerance(options.tolerance);
  const auto is_float = solutions_internal::float_objectives(reference, solution);
  SolutionEvaluation result;
  result.exact_arithmetic = std::find(is_float.begin(), is_float.end(), true) == is_float.end();
  result.solver_epsilon = parse_epsilon(solution.solver().epsilon);
  result.solver_claims_exact = result.solver_epsilon.num == 0;
  result.covered_per_epsilon.assign(epsilons.size(), 0);
  for (std::uint64_t q = 0; q < reference.query_count(); ++q) {
    QueryEvaluation e;
    e.query = q;
    e.reference_status = reference.status(q);
    e.solution_status = solution.status(q);
    if (e.reference_status == QueryStatus::solved && e.solution_status == QueryStatus::solved) {
      evaluate_front_of(reference, solution, epsilons, options, is_float, e);
      e.dominated = result.solver_claims_exact && !e.front->dominated_by_reference.empty();
      e.failed = e.dominated;
      for (std::size_t k = 0; k < epsilons.size(); ++k) {
        if (e.outcome(k) == QueryOutcome::covered) ++result.covered_per_epsilon[k];
        // Below the solver's own ε, not covering is the approximation it announced.
        if (!(epsilons[k] < result.solver_epsilon))
          e.failed = e.failed || !e.front->coverage[k].covered;
      }
    } else if (e.reference_status == QueryStatus::solved) {
      e.failed = true;  // the solver did not solve a query the reference solved
    } else {
      // No reference front to compare with: only a different outcome is a failure (a solver
      // reporting a front where the reference found the query disconnected, say).
      e.failed = e.solution_status == QueryStatus::solved &&
                 e.reference_status == QueryStatus::disconnected;
    }
    result.failed = result.failed || e.failed;
    result.queries.push_back(std::move(e));
  }
  return result;
}

}  // namespace mosb
