#include "mosb/solution_eval.hpp"

#include <type_traits>

#include "mosb/error.hpp"

namespace mosb {
namespace {

bool all_integer(const SolutionReader& r) {
  for (std::size_t i = 0; i < r.objective_count(); ++i) {
    const bool integral = r.visit_column(
        i, [](auto span) { return std::is_integral_v<typename decltype(span)::value_type>; });
    if (!integral) return false;
  }
  return true;
}

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

}  // namespace

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
                                      std::span<const Ratio> epsilons, const EvalOptions& options) {
  check_same_binding(reference, solution);
  const std::size_t d = reference.objective_count();
  const bool integer = all_integer(reference) && all_integer(solution);
  SolutionEvaluation result;
  result.exact_arithmetic = integer;
  result.solver_claims_exact = parse_epsilon(solution.solver().epsilon).num == 0;
  result.covered_per_epsilon.assign(epsilons.size(), 0);
  for (std::uint64_t q = 0; q < reference.query_count(); ++q) {
    QueryEvaluation e;
    e.query = q;
    e.reference_status = reference.status(q);
    e.solution_status = solution.status(q);
    if (e.reference_status == QueryStatus::solved && e.solution_status == QueryStatus::solved) {
      const auto run = [&](auto tag) {
        using T = decltype(tag);
        const auto s = gather<T>(solution, q), r = gather<T>(reference, q);
        return evaluate_front(FrontView<T>{s, d}, FrontView<T>{r, d}, epsilons, options);
      };
      e.front = integer ? run(std::uint64_t{}) : run(double{});
      if (e.front->worst_reference) {
        const std::uint64_t row = reference.front_begin(q) + *e.front->worst_reference;
        for (std::size_t i = 0; i < d; ++i)
          e.worst_reference_values.push_back(reference.value_as_double(i, row));
      }
      for (std::size_t k = 0; k < epsilons.size(); ++k) {
        if (e.front->coverage[k].covered)
          ++result.covered_per_epsilon[k];
        else
          e.failed = true;
      }
      if (result.solver_claims_exact && !e.front->dominated_by_reference.empty()) e.failed = true;
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
