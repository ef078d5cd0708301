// Checks of a solution file against its instance (spec/SOLUTIONS.md §5): the binding, then the
// payload, then every disconnected claim, then every front mutually non-dominated and
// duplicate-free, then every stored path.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/graph_reader.hpp"
#include "mosb/solution_file.hpp"

namespace mosb {

// spec/SOLUTIONS.md §6: the reference a query set declares (section kind 17 and the metadata
// `queries.<set>.reference.objective`, `.source` and `.units`).
enum class ReferenceUnits {
  // Moving AI's: 1 per straight and sqrt 2 per diagonal step, against an objective that costs 10
  // and 14 (the games `length`). The default when `.units` is absent.
  octile,
  objective,  // the objective's own unit
};
struct QueryReferenceDeclaration {
  std::string objective, source;
  ReferenceUnits units = ReferenceUnits::octile;
};
// nullopt when the query set carries no reference.
std::optional<QueryReferenceDeclaration> declared_reference(const GraphReader& instance,
                                                            const std::string& query_set);

// Whether the smallest value c* of the reference's objective in an exact front agrees with the
// query's optimum L*. Octile: the bracket c*/10 <= L* + tau and L* <= (sqrt 2 / 1.4) c*/10 + tau,
// tau = 1e-5 max(1, L*). Objective: |c* - L*| <= 1e-9 max(1, L*). nullopt when it holds, else the
// "[reference] ..." message showing both values and naming the objective and the source.
std::optional<std::string> reference_problem(double c_star, double l_star,
                                             const QueryReferenceDeclaration& reference);

// A cost as messages and reports print it: an integer as an integer, any other value in the
// shortest text that reads back to the same double (so two different values never print alike).
std::string cost_text(double value);
// "(a, b, c)", each value as cost_text prints it.
std::string cost_vector_text(std::span<const double> values);

// A front's vectors (row-major, d >= 1 values each) that are not Pareto-optimal within it:
// weakly dominated by another of its vectors, or equal to one before it (the first of equal
// vectors is kept). What `solutions import --nondominated` drops and verify's [dominated] and
// [duplicate] refuse. Row indices, increasing; empty when the vectors are mutually
// non-dominated and distinct. O(k log k) for d <= 3 (one sort and one sweep; a k-d tree for
// d >= 4, as verify_solutions).
std::vector<std::size_t> dominated_rows(std::span<const double> rows, std::size_t d);

// The pair verify_solutions names: row `dominated` is weakly dominated by row `by` (equal to it,
// for a duplicate), the first such row in lexicographic order; nullopt when there is none.
struct DominatedRow {
  std::size_t dominated = 0, by = 0;
};
std::optional<DominatedRow> first_dominated_row(std::span<const double> rows, std::size_t d);
// How the pair is named: "[duplicate] vector (4, 4) appears twice" or "[dominated] vector (3, 9)
// is dominated by (3, 8)" (each value in the shortest text that reads back the same).
std::string dominated_row_text(std::span<const double> rows, std::size_t d, DominatedRow pair);

// The first problem of a front as a solver returned it (spec/RUN.md §3, rule 1), `rows` row-major
// with d >= 1 values each: two equal vectors ("[duplicate] vector (1, 9) appears twice"), or, when
// `exact` (the solver claims ε = 0), a vector another weakly dominates ("[dominated] vector
// (3, 9) is dominated by (3, 8)"); nullopt when there is none. An ε-approximate front may hold
// vectors its own others dominate. O(k log k) for d <= 3.
std::optional<std::string> front_problem(std::span<const double> rows, std::size_t d, bool exact);

// The first problem, as one line naming the query (and both vectors, or the path step), or
// nullopt. `instance` must be opened with VerifyLevel::full (paths walk its CSR). Cost: the
// payload, plus O(k log k) per front of k vectors for d <= 3 (a lexicographic sort and a sweep;
// for d >= 4 the sweep asks a k-d tree, src/front_index.hpp), plus the path lengths times the
// out-degrees along them, plus O(n + m) per distinct start of the queries claimed `disconnected`
// (one breadth-first search each over the forward CSR: a reachable goal is "[disconnected] ... (a
// wrong answer)"). Integer path costs are summed exactly in u64 and compared exactly with the
// stored sums. When the query set declares a reference (section
// kind 17 and `queries.<set>.reference.objective`, of any source) for an objective of the view,
// each solved front's smallest value of that objective is checked against the query's optimum in
// the declared units (reference_problem, "[reference]"); the source's name appears only in the
// message.
std::optional<std::string> verify_solutions(const SolutionReader& solutions,
                                            const GraphReader& instance);

}  // namespace mosb
