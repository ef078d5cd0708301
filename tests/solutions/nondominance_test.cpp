// find_weakly_dominated (lib/solutions/src/nondominance.hpp) against the quadratic definition on
// random small fronts: d = 1..8, values from tiny ranges (ties and duplicates), mutually
// non-dominated fronts on a plane, and the three value types solution files store.
#include "nondominance.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "mosb/random.hpp"

using mosb::SplitMix64;
using mosb::solutions_internal::DominatedPair;
using mosb::solutions_internal::find_weakly_dominated;

namespace {

// The definition: in lexicographic order (equal vectors by index), the first vector weakly
// dominated by one before it, and the first such one.
template <class T>
std::optional<DominatedPair> brute_force(const std::vector<T>& rows, std::size_t d) {
  const std::size_t n = rows.size() / d;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  const auto at = [&](std::size_t k) { return rows.begin() + static_cast<std::ptrdiff_t>(k * d); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(at(a), at(a) + static_cast<std::ptrdiff_t>(d), at(b),
                                        at(b) + static_cast<std::ptrdiff_t>(d));
  });
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < j; ++k) {
      bool dominates = true;
      for (std::size_t i = 0; i < d; ++i)
        dominates = dominates && at(order[k])[i] <= at(order[j])[i];
      if (dominates) return DominatedPair{order[j], order[k]};
    }
  return std::nullopt;
}

// A value of type T from a small integer: shifted negative for i64, halved for double.
template <class T>
T make(std::uint64_t x) {
  if constexpr (std::is_same_v<T, std::int64_t>)
    return static_cast<std::int64_t>(x) - 3;
  else if constexpr (std::is_same_v<T, double>)
    return static_cast<double>(x) / 2;
  else
    return x;
}

// n vectors; `plane`: coordinates summing to a constant (mutually non-dominated unless equal).
template <class T>
std::vector<T> random_front(SplitMix64& rng, std::size_t n, std::size_t d, std::uint64_t range,
                            bool plane) {
  std::vector<T> rows(n * d);
  for (std::size_t k = 0; k < n; ++k) {
    std::uint64_t left = range * d;
    for (std::size_t i = 0; i < d; ++i) {
      std::uint64_t x = rng.uniform(0, range);
      if (plane) x = i + 1 == d ? left : std::min(x, left);
      left -= plane ? x : 0;
      rows[k * d + i] = make<T>(x);
    }
  }
  return rows;
}

template <class T>
void compare_on_random_fronts(std::uint64_t seed) {
  SplitMix64 rng(seed);
  std::size_t found = 0, clean = 0;
  for (int round = 0; round < 3000; ++round) {
    // Every 10th front large enough for a front index several levels deep (d >= 4).
    const std::size_t d = 1 + round % 8,
                      n = round % 10 == 9 ? rng.uniform(100, 300) : rng.uniform(0, 40);
    const auto rows = random_front<T>(rng, n, d, rng.uniform(1, 12), round % 3 != 0);
    const auto expected = brute_force(rows, d);
    const auto got = find_weakly_dominated<T>(rows, d);
    REQUIRE(got.has_value() == expected.has_value());
    if (!got) {
      ++clean;
      continue;
    }
    ++found;
    CHECK(got->dominated == expected->dominated);
    CHECK(got->by == expected->by);
  }
  CHECK(found > 500);  // both outcomes exercised
  CHECK(clean > 500);
}

}  // namespace

TEST_CASE("nondominance: u64 fronts agree with the quadratic definition") {
  compare_on_random_fronts<std::uint64_t>(1);
}

TEST_CASE("nondominance: i64 fronts (negative values) agree with the quadratic definition") {
  compare_on_random_fronts<std::int64_t>(2);
}

TEST_CASE("nondominance: f64 fronts agree with the quadratic definition") {
  compare_on_random_fronts<double>(3);
}

TEST_CASE("nondominance: a duplicate names both copies, a dominated vector its dominator") {
  const std::vector<std::uint64_t> duplicate{5, 1, 1, 2, 3, 4, 2, 3, 4};
  const auto pair = find_weakly_dominated<std::uint64_t>(duplicate, 3);
  REQUIRE(pair);
  CHECK(pair->dominated == 2);
  CHECK(pair->by == 1);
  // (1,2,3,4) dominates (2,2,3,4); (0,9,9,9) and (3,0,0,0) are incomparable to both.
  const std::vector<double> dominated{2, 2, 3, 4, 0, 9, 9, 9, 3, 0, 0, 0, 1, 2, 3, 4.5};
  CHECK_FALSE(find_weakly_dominated<double>(dominated, 4));
  const std::vector<double> dominated2{2, 2, 3, 4, 0, 9, 9, 9, 3, 0, 0, 0, 1, 2, 3, 4};
  const auto pair2 = find_weakly_dominated<double>(dominated2, 4);
  REQUIRE(pair2);
  CHECK(pair2->dominated == 0);
  CHECK(pair2->by == 3);
  CHECK_FALSE(find_weakly_dominated<std::int64_t>(std::vector<std::int64_t>{}, 3));
  CHECK_FALSE(find_weakly_dominated<std::int64_t>(std::vector<std::int64_t>{-1, 2}, 2));
}

TEST_CASE("weakly_dominated_rows: every row outside the non-dominated subset, first copies kept") {
  // What `solutions import --nondominated` drops (issue 33 §4), against the definition: row j is
  // dropped iff another row weakly dominates it, unless that row equals it and comes later.
  using mosb::solutions_internal::weakly_dominated_rows;
  SplitMix64 rng(33);
  for (int round = 0; round < 2000; ++round) {
    const std::size_t d = 1 + round % 5, n = rng.uniform(0, 30);
    const auto rows = random_front<double>(rng, n, d, rng.uniform(1, 8), round % 2 == 0);
    std::vector<std::size_t> expected;
    for (std::size_t j = 0; j < n; ++j) {
      bool dropped = false;
      for (std::size_t k = 0; k < n && !dropped; ++k) {
        if (k == j) continue;
        bool dominates = true, equal = true;
        for (std::size_t i = 0; i < d; ++i) {
          dominates = dominates && rows[k * d + i] <= rows[j * d + i];
          equal = equal && rows[k * d + i] == rows[j * d + i];
        }
        dropped = dominates && (!equal || k < j);
      }
      if (dropped) expected.push_back(j);
    }
    CAPTURE(round);
    CHECK(weakly_dominated_rows<double>(rows, d) == expected);
  }
}
