// FrontIndex (lib/solutions/src/front_index.hpp) against scans: orthant queries with and without
// a rank limit, and the minimum of a score that grows with each coordinate, in d = 1..8 for the
// three value types, on fronts with ties, duplicates, near-plane vectors and extreme values.
#include "front_index.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <vector>

#include "mosb/random.hpp"

using mosb::SplitMix64;
using mosb::solutions_internal::FrontIndex;

namespace {

// A value of type T: from a tiny range (ties), a plane-like spread, or the type's extremes.
template <class T>
T random_value(SplitMix64& rng, int mode) {
  const std::uint64_t x = mode == 0 ? rng.uniform(0, 4) : rng.uniform(0, 1'000'000);
  if (mode == 2 && rng.uniform(0, 3) == 0)
    return rng.uniform(0, 1) == 0 ? std::numeric_limits<T>::max()
                                  : std::numeric_limits<T>::lowest();
  if constexpr (std::is_same_v<T, std::int64_t>)
    return static_cast<std::int64_t>(x) - 500'000;
  else if constexpr (std::is_same_v<T, double>)
    return static_cast<double>(x) / 3;
  else
    return x;
}

template <class T>
void compare_with_scans(std::uint64_t seed) {
  SplitMix64 rng(seed);
  std::size_t hits = 0, misses = 0;
  for (int round = 0; round < 400; ++round) {
    const std::size_t d = 1 + round % 8,
                      n = round % 4 == 3 ? rng.uniform(200, 600) : rng.uniform(0, 30);
    const int mode = round / 8 % 3;
    std::vector<T> rows(n * d);
    for (auto& v : rows) v = random_value<T>(rng, mode);
    // Some rows copied from others, one coordinate now and then raised: duplicates, dominance.
    for (std::size_t k = 1; k < n; ++k)
      if (rng.uniform(0, 4) == 0) {
        const std::size_t from = rng.uniform(0, k - 1);
        std::copy_n(rows.begin() + static_cast<std::ptrdiff_t>(from * d), d,
                    rows.begin() + static_cast<std::ptrdiff_t>(k * d));
      }
    std::vector<std::size_t> rank(n);
    std::iota(rank.begin(), rank.end(), std::size_t{0});
    for (std::size_t k = n; k > 1; --k) std::swap(rank[k - 1], rank[rng.uniform(0, k - 1)]);
    const FrontIndex<T> plain(rows, d), ranked(rows, d, rank);
    for (int query = 0; query < 50; ++query) {
      // The bound: a row itself (its own orthant), a row moved a little, or random values.
      std::vector<T> bound(d);
      const std::size_t from = n > 0 ? rng.uniform(0, n - 1) : 0;
      for (std::size_t i = 0; i < d; ++i) {
        const bool own = n > 0 && query % 3 != 2;
        bound[i] = own ? rows[from * d + i] : random_value<T>(rng, mode);
        if (own && query % 3 == 1 && bound[i] > std::numeric_limits<T>::lowest() &&
            rng.uniform(0, 1) == 0)
          bound[i] = static_cast<T>(bound[i] - 1);
      }
      const std::size_t limit = rng.uniform(0, n + 1);
      bool any = false, any_ranked = false;
      for (std::size_t k = 0; k < n; ++k) {
        bool below = true;
        for (std::size_t i = 0; i < d; ++i) below = below && rows[k * d + i] <= bound[i];
        any = any || below;
        any_ranked = any_ranked || (below && rank[k] < limit);
      }
      CAPTURE(round);
      CAPTURE(query);
      CHECK(plain.any_at_most(bound.data()) == any);
      CHECK(ranked.any_at_most(bound.data(), limit) == any_ranked);
      (any ? hits : misses) += 1;
      // The minimum over the rows of the largest coordinate above the bound's (0 when below).
      const auto score = [&](const T* x, double) {
        double worst = 0;
        for (std::size_t i = 0; i < d; ++i)
          if (x[i] > bound[i])
            worst = std::max(worst, static_cast<double>(x[i]) - static_cast<double>(bound[i]));
        return worst;
      };
      double expected = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < n; ++k) expected = std::min(expected, score(&rows[k * d], 0.0));
      CHECK(plain.minimum(score, std::numeric_limits<double>::infinity(), std::less<>()) ==
            expected);
    }
  }
  CHECK(hits > 1000);  // both answers exercised
  CHECK(misses > 1000);
}

}  // namespace

TEST_CASE("front index: u64 queries agree with scans") {
  compare_with_scans<std::uint64_t>(1);
}

TEST_CASE("front index: i64 queries (negative values) agree with scans") {
  compare_with_scans<std::int64_t>(2);
}

TEST_CASE("front index: f64 queries agree with scans") {
  compare_with_scans<double>(3);
}
