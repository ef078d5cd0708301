// Whether a front (minimisation) holds two vectors one of which weakly dominates the other (no
// worse in every objective; equal vectors included): the [duplicate] and [dominated] checks of
// spec/SOLUTIONS.md §5. Internal to lib/solutions; generic over the stored value type.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace mosb::solutions_internal {

// Row indices into the front: `dominated` is weakly dominated by `by` (`by` != `dominated`).
struct DominatedPair {
  std::size_t dominated, by;
};

// `rows` holds the front row-major, d values per vector (d >= 1). The pair reported is the one
// of the quadratic definition: in lexicographic order of the vectors, `dominated` is the first
// vector weakly dominated by a vector at or before it, and `by` the lexicographically smallest
// such vector (among equal vectors, the first in that order). nullopt when the vectors are
// mutually non-dominated and distinct. Cost: O(n log n) for d <= 3 (a sort and a sweep; d = 3
// keeps the staircase of (second, third) values in a balanced tree); for d >= 4 the sweep asks the
// front index (front_index.hpp), restricted to the vectors before the one asked.
// Defined for std::uint64_t, std::int64_t and double (no NaN).
template <class T>
std::optional<DominatedPair> find_weakly_dominated(std::span<const T> rows, std::size_t d);

// Every row weakly dominated by a row before it in that lexicographic order (equal vectors: by
// index), i.e. every row outside the non-dominated subset that keeps the first of equal vectors;
// increasing. Empty when find_weakly_dominated finds nothing. The same sweep and cost.
template <class T>
std::vector<std::size_t> weakly_dominated_rows(std::span<const T> rows, std::size_t d);

extern template std::vector<std::size_t> weakly_dominated_rows<std::uint64_t>(
    std::span<const std::uint64_t>, std::size_t);
extern template std::vector<std::size_t> weakly_dominated_rows<double>(std::span<const double>,
                                                                       std::size_t);
extern template std::optional<DominatedPair> find_weakly_dominated<std::uint64_t>(
    std::span<const std::uint64_t>, std::size_t);
extern template std::optional<DominatedPair> find_weakly_dominated<std::int64_t>(
    std::span<const std::int64_t>, std::size_t);
extern template std::optional<DominatedPair> find_weakly_dominated<double>(std::span<const double>,
                                                                           std::size_t);

}  // namespace mosb::solutions_internal
