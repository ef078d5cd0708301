#include "mosb/solution_verify.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <string_view>
#include <tuple>

#include "mosb/internal/number_text.hpp"
#include "nondominance.hpp"

namespace mosb {

namespace {

// The front of query q as rows of d doubles, one buffer: exact for every integer cost (the writer
// refuses integers above 2^53) and for f32/f64 costs. Read a column at a time, in its own type.
std::vector<double> front_of(const SolutionReader& s, std::uint64_t begin, std::uint64_t size) {
  const std::size_t d = s.objective_count();
  std::vector<double> rows(size * d);
  for (std::size_t i = 0; i < d; ++i)
    s.visit_column(i, [&](auto column) {
      for (std::uint64_t k = 0; k < size; ++k)
        rows[k * d + i] = static_cast<double>(column[begin + k]);
    });
  return rows;
}

// [duplicate] and [dominated]: the pair the quadratic definition names, found in O(k log k) for
// d <= 3 (nondominance.hpp).
std::optional<std::string> dominance_problem(std::span<const double> rows, std::size_t d,
                                             const std::string& label) {
  const auto pair = first_dominated_row(rows, d);
  if (!pair) return std::nullopt;
  return label + dominated_row_text(rows, d, *pair);
}

// The first pair of equal rows in lexicographic order, or nullopt.
std::optional<std::size_t> first_repeated_row(std::span<const double> rows, std::size_t d) {
  std::vector<std::size_t> order(rows.size() / d);
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  const auto row = [&](std::size_t k) { return rows.subspan(k * d, d); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const auto x = row(a), y = row(b);
    return std::lexicographical_compare(x.begin(), x.end(), y.begin(), y.end());
  });
  for (std::size_t k = 1; k < order.size(); ++k)
    if (std::equal(row(order[k]).begin(), row(order[k]).end(), row(order[k - 1]).begin()))
      return order[k];
  return std::nullopt;
}

// A path's cost so far: integer objectives summed exactly in u64 (a file's integer sums are at most
// 2^53, so a sum that overflows u64 cannot match), float objectives in f64 (SOLUTIONS.md §5).
struct PartialSum {
  std::vector<std::uint64_t> integer;  // one per objective; 0 for a float objective
  std::vector<double> real;            // one per objective; 0 for an integer objective
  bool overflow = false;               // some integer sum passed 2^64 - 1
  // For sort and unique (not a defaulted <=>: clang-tidy 14 misreads it as a 0 literal).
  bool operator<(const PartialSum& o) const {
    return std::tie(integer, real, overflow) < std::tie(o.integer, o.real, o.overflow);
  }
  bool operator==(const PartialSum& o) const = default;
};

PartialSum extended(PartialSum sum, const GraphReader& g, std::span<const std::size_t> objectives,
                    const std::vector<bool>& is_float, std::uint64_t arc) {
  for (std::size_t i = 0; i < is_float.size(); ++i) {
    if (is_float[i]) {
      sum.real[i] += g.cost_as<double>(objectives[i])[arc];
    } else {
      const auto cost = g.cost_as<std::uint64_t>(objectives[i])[arc];
      sum.overflow = sum.overflow || __builtin_add_overflow(sum.integer[i], cost, &sum.integer[i]);
    }
  }
  return sum;
}

// Whether the arcs' sum is the stored vector: exactly for integers, within 1e-9 per arc (relative)
// for floats.
bool sum_matches(const PartialSum& sum, std::span<const double> vector,
                 const std::vector<bool>& is_float, std::size_t path_size) {
  if (sum.overflow) return false;
  for (std::size_t i = 0; i < is_float.size(); ++i) {
    if (!is_float[i]) {
      // The stored value is an integer of at most 2^53 (verify_payload), exact as a double.
      if (static_cast<double>(sum.integer[i]) != vector[i] ||
          sum.integer[i] != static_cast<std::uint64_t>(vector[i]))
        return false;
      continue;
    }
    const auto tolerance =
        1e-9 * static_cast<double>(path_size) * std::max(1.0, std::abs(vector[i]));
    if (std::abs(sum.real[i] - vector[i]) > tolerance) return false;
  }
  return true;
}

std::string sum_text(const PartialSum& sum, const std::vector<bool>& is_float) {
  if (sum.overflow) return "more than 2^64 - 1";
  std::string text = "(";
  for (std::size_t i = 0; i < is_float.size(); ++i)
    text +=
        (i ? ", " : "") + (is_float[i] ? cost_text(sum.real[i]) : std::to_string(sum.integer[i]));
  return text + ")";
}

// [path] and [path-cost]: the path runs from the query's start to its goal along arcs, and some
// choice among parallel arcs sums to the stored vector (SOLUTIONS.md §5).
std::optional<std::string> path_problem(const SolutionReader& s, const GraphReader& g,
                                        std::span<const std::size_t> objectives,
                                        std::span<const std::uint64_t> offsets,
                                        std::span<const std::uint32_t> targets, const Query& query,
                                        std::span<const std::uint32_t> path,
                                        std::span<const double> vector, const std::string& where) {
  const std::size_t d = s.objective_count();
  if (path.empty()) return where + "[path] is empty";
  if (path.front() != query.start || path.back() != query.goal)
    return where + "[path] runs from " + std::to_string(path.front()) + " to " +
           std::to_string(path.back()) + ", the query from " + std::to_string(query.start) +
           " to " + std::to_string(query.goal);
  std::vector<bool> is_float(d);
  for (std::size_t i = 0; i < d; ++i) is_float[i] = format::is_float(s.objective_type(i));
  // Partial sums reachable by some choice among parallel arcs.
  std::vector<PartialSum> sums{
      PartialSum{std::vector<std::uint64_t>(d, 0), std::vector<double>(d, 0.0), false}};
  for (std::size_t step = 0; step + 1 < path.size(); ++step) {
    std::vector<PartialSum> next;
    for (auto arc = offsets[path[step]]; arc < offsets[path[step] + 1]; ++arc) {
      if (targets[arc] != path[step + 1]) continue;
      for (const auto& sum : sums) next.push_back(extended(sum, g, objectives, is_float, arc));
    }
    if (next.empty())
      return where + "[path] no arc from " + std::to_string(path[step]) + " to " +
             std::to_string(path[step + 1]);
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    sums = std::move(next);
  }
  const bool matches = std::any_of(sums.begin(), sums.end(), [&](const auto& sum) {
    return sum_matches(sum, vector, is_float, path.size());
  });
  if (!matches)
    return where + "[path-cost] the arcs sum to " + sum_text(sums.front(), is_float) +
           (sums.size() > 1 ? " (or another parallel-arc choice)" : "") +
           ", not to the stored vector";
  return std::nullopt;
}

// [disconnected]: every query the file calls disconnected must have its goal unreachable from its
// start. One breadth-first search over the forward CSR per distinct start, O(n + m) each.
std::optional<std::string> disconnected_problem(const SolutionReader& s,
                                                std::span<const Query> queries,
                                                std::span<const std::uint64_t> offsets,
                                                std::span<const std::uint32_t> targets,
                                                std::uint64_t vertex_count) {
  std::map<std::uint32_t, std::vector<std::uint64_t>> by_start;  // ordered: reports are stable
  for (std::uint64_t q = 0; q < s.query_count(); ++q)
    if (s.status(q) == QueryStatus::disconnected) by_start[queries[q].start].push_back(q);
  std::vector<std::uint32_t> seen(vertex_count, 0);  // the search number that reached a vertex
  std::vector<std::uint32_t> frontier;
  std::uint32_t search = 0;
  for (const auto& [start, claims] : by_start) {
    ++search;
    frontier.assign(1, start);
    seen[start] = search;
    for (std::size_t k = 0; k < frontier.size(); ++k) {
      const auto u = frontier[k];
      for (auto arc = offsets[u]; arc < offsets[u + 1]; ++arc)
        if (seen[targets[arc]] != search) {
          seen[targets[arc]] = search;
          frontier.push_back(targets[arc]);
        }
    }
    for (const auto q : claims)
      if (seen[queries[q].goal] == search)
        return "query " + std::to_string(q) + ": [disconnected] the goal " +
               std::to_string(queries[q].goal) + " is reachable from the start " +
               std::to_string(start) + " (a wrong answer)";
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> reference_problem(double c_star, double l_star,
                                             const QueryReferenceDeclaration& reference) {
  const std::string head = "[reference] the smallest " + reference.objective +
                           " c* = " + cost_text(c_star) + " does not match the " +
                           reference.source + " optimum L* = " + cost_text(l_star) + ": ";
  if (reference.units == ReferenceUnits::objective) {
    // The objective's own unit: an exact front's smallest value is the optimum, up to the
    // rounding of a printed real.
    const double tau = 1e-9 * std::max(1.0, l_star);
    if (std::fabs(c_star - l_star) <= tau) return std::nullopt;
    return head + "|c* - L*| > tau (spec/SOLUTIONS.md section 6)";
  }
  // Octile: Moving AI prints `optimal` with 6 or more significant digits (relative rounding at
  // most 5e-6); twice that covers it (spec/SOLUTIONS.md §6).
  const double tau = 1e-5 * std::max(1.0, l_star);
  const double low = c_star / 10, high = std::sqrt(2.0) / 1.4 * c_star / 10;
  if (low <= l_star + tau && l_star <= high + tau) return std::nullopt;
  return head +
         (low > l_star + tau ? "c*/10 = " + cost_text(low) + " > L* + tau"
                             : "L* > (sqrt 2/1.4) c*/10 + tau = " + cost_text(high + tau)) +
         " (spec/SOLUTIONS.md section 6)";
}

std::optional<QueryReferenceDeclaration> declared_reference(const GraphReader& instance,
                                                            const std::string& query_set) {
  if (!instance.query_reference(query_set)) return std::nullopt;
  const std::string key = "queries." + query_set + ".reference.";
  const auto& metadata = instance.metadata();
  QueryReferenceDeclaration d;
  d.objective = metadata.get(key + "objective").value_or("");
  d.source = metadata.get(key + "source").value_or("");
  d.units = metadata.get(key + "units") == "objective" ? ReferenceUnits::objective
                                                       : ReferenceUnits::octile;
  return d;
}

std::string cost_text(double value) {
  // Integers (every integer path sum, up to 2^53) as integers: to_chars' shortest form would
  // print 1000000000 as 1e+09.
  if (value == std::floor(value) && std::fabs(value) <= 9007199254740992.0)
    return std::to_string(static_cast<std::int64_t>(value));
  return shortest_text(value);
}

std::string cost_vector_text(std::span<const double> values) {
  std::string text = "(";
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ", " : "") + cost_text(values[i]);
  return text + ")";
}

std::vector<std::size_t> dominated_rows(std::span<const double> rows, std::size_t d) {
  return solutions_internal::weakly_dominated_rows<double>(rows, d);
}

std::optional<DominatedRow> first_dominated_row(std::span<const double> rows, std::size_t d) {
  const auto pair = solutions_internal::find_weakly_dominated<double>(rows, d);
  if (!pair) return std::nullopt;
  return DominatedRow{pair->dominated, pair->by};
}

std::string dominated_row_text(std::span<const double> rows, std::size_t d, DominatedRow pair) {
  const auto vector = [&](std::size_t row) {
    return std::vector<double>(rows.begin() + static_cast<std::ptrdiff_t>(row * d),
                               rows.begin() + static_cast<std::ptrdiff_t>((row + 1) * d));
  };
  const auto v = vector(pair.dominated), w = vector(pair.by);
  return v == w ? "[duplicate] vector " + cost_vector_text(v) + " appears twice"
                : "[dominated] vector " + cost_vector_text(v) + " is dominated by " +
                      cost_vector_text(w);
}

std::optional<std::string> verify_solutions(const SolutionReader& s, const GraphReader& g) {
  try {
    s.check_bound_to(g);
  } catch (const Error& e) {
    return e.what();
  }
  if (auto problem = s.verify_payload()) return problem;
  g.require_verified(VerifyLevel::full, "solutions verify");
  const std::size_t d = s.objective_count();
  const auto queries = g.queries(s.query_set());
  const auto objectives = s.instance_objectives(g);
  const auto offsets = g.forward_offsets();
  const auto targets = g.forward_targets();
  // The optima the query set declares (kind 17 and its metadata), checked as their declared units
  // say, when the view holds their objective; the source only names them in messages.
  const auto reference = g.query_reference(s.query_set());
  const auto declared = declared_reference(g, s.query_set());
  std::optional<std::size_t> reference_objective;
  if (declared)
    for (std::size_t i = 0; i < d; ++i)
      if (declared->objective == s.objective_name(i)) reference_objective = i;
  if (auto problem = disconnected_problem(s, queries, offsets, targets, g.vertex_count()))
    return problem;
  for (std::uint64_t q = 0; q < s.query_count(); ++q) {
    const std::string label = "query " + std::to_string(q) + ": ";
    const auto begin = s.front_begin(q), size = s.front_size(q);
    const auto front = front_of(s, begin, size);
    const auto vector = [&](std::uint64_t k) { return std::span(front).subspan(k * d, d); };
    if (auto problem = dominance_problem(front, d, label)) return problem;
    if (reference_objective && size > 0 && s.status(q) == QueryStatus::solved) {
      double c_star = INFINITY;
      for (std::uint64_t k = 0; k < size; ++k)
        c_star = std::min(c_star, vector(k)[*reference_objective]);
      if (auto problem = reference_problem(c_star, (*reference)[q], *declared))
        return label + *problem;
    }
    if (!s.has_paths()) continue;
    for (std::uint64_t k = 0; k < size; ++k) {
      const std::string where = label + "path of vector " + cost_vector_text(vector(k)) + ": ";
      if (auto problem = path_problem(s, g, objectives, offsets, targets, queries[q],
                                      s.path(begin + k), vector(k), where))
        return problem;
    }
  }
  return std::nullopt;
}

std::optional<std::string> front_problem(std::span<const double> rows, std::size_t d, bool exact) {
  if (d == 0 || rows.size() < 2 * d) return std::nullopt;
  if (exact) {
    const auto pair = first_dominated_row(rows, d);
    return pair ? std::optional(dominated_row_text(rows, d, *pair)) : std::nullopt;
  }
  const auto repeated = first_repeated_row(rows, d);
  return repeated ? std::optional(dominated_row_text(rows, d, {*repeated, *repeated}))
                  : std::nullopt;
}

}  // namespace mosb
