#include "mosb/eval.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/random.hpp"

using namespace mosb;

namespace {

using Front = std::vector<std::uint64_t>;

FrontView<std::uint64_t> view(const Front& f, std::size_t d) {
  return {f, d};
}

// The per-coordinate ε that p needs to cover q, as a ratio, computed without the library's
// comparison: (p-q)/q, 0 when p ≤ q, infinite when q = 0 < p.
Ratio coordinate_need(std::uint64_t p, std::uint64_t q) {
  if (p <= q) return {0, 1};
  if (q == 0) return {1, 0};
  return {p - q, q};
}

// Brute force O(|S||R|d): the ε each reference vector needs; uncovered at ε means need > ε.
std::vector<Ratio> brute_needs(const Front& s, const Front& r, std::size_t d) {
  std::vector<Ratio> needs;
  for (std::size_t b = 0; b < r.size() / d; ++b) {
    Ratio best{1, 0};
    for (std::size_t a = 0; a < s.size() / d; ++a) {
      Ratio worst{0, 1};
      for (std::size_t i = 0; i < d; ++i) {
        const Ratio e = coordinate_need(s[a * d + i], r[b * d + i]);
        if (worst < e) worst = e;
      }
      if (worst < best) best = worst;
    }
    needs.push_back(best);
  }
  return needs;
}

// Brute force of the strict reading: some p with p ≤ (1+ε)q everywhere and < somewhere, in
// 128-bit integer arithmetic: den·p vs (den+num)·q.
std::vector<std::size_t> brute_strict_uncovered(const Front& s, const Front& r, std::size_t d,
                                                Ratio e) {
  __extension__ typedef unsigned __int128 u128;
  std::vector<std::size_t> out;
  for (std::size_t b = 0; b < r.size() / d; ++b) {
    bool covered = false;
    for (std::size_t a = 0; a < s.size() / d && !covered; ++a) {
      bool all = true, some = false;
      for (std::size_t i = 0; i < d; ++i) {
        const u128 lhs = static_cast<u128>(e.den) * s[a * d + i];
        const u128 rhs = static_cast<u128>(e.den + e.num) * r[b * d + i];
        all = all && lhs <= rhs;
        some = some || lhs < rhs;
      }
      covered = all && some;
    }
    if (!covered) out.push_back(b);
  }
  return out;
}

Front random_front(SplitMix64& rng, std::size_t n, std::size_t d, std::uint64_t hi) {
  Front f(n * d);
  for (auto& v : f) v = rng.uniform(0, hi);
  return f;
}

const std::vector<Ratio> kEpsilons = {{0, 1}, {1, 100}, {1, 20}, {1, 10}, {1, 2}};

}  // namespace

TEST_CASE("achieved_epsilon_text rounds up at the 9th digit, exact decimals when exact") {
  FrontEvaluation f;
  f.achieved_value = 0.05;
  CHECK(achieved_epsilon_text(f, false) == "0.05");
  f.achieved_value = 1.0 / 3;
  CHECK(achieved_epsilon_text(f, false) == "0.333333334");
  f.achieved_value = 0;
  CHECK(achieved_epsilon_text(f, false) == "0");
  f.achieved_value = std::numeric_limits<double>::infinity();
  CHECK(achieved_epsilon_text(f, false) == "inf");
  f.achieved = Ratio{1, 4};
  CHECK(achieved_epsilon_text(f, true) == "0.25");
  f.achieved = Ratio{1, 0};
  CHECK(achieved_epsilon_text(f, true) == "inf");
}

TEST_CASE("parse_epsilon gives exact reduced ratios and rejects the rest") {
  CHECK(parse_epsilon("0.05") == Ratio{1, 20});
  CHECK(parse_epsilon("0.050").num == 1);
  CHECK(parse_epsilon("0.050").den == 20);
  CHECK(parse_epsilon("0") == Ratio{0, 1});
  CHECK(parse_epsilon(".5") == Ratio{1, 2});
  CHECK(parse_epsilon("2") == Ratio{2, 1});
  for (const char* bad : {"", ".", "-0.1", "1e-2", "0.1.2", "abc", "0.1234567890123456789"})
    CHECK_THROWS_AS(parse_epsilon(bad), Error);
}

TEST_CASE("parse_epsilon takes 18 significant digits on each side of the point, as specified") {
  // 10 + 9 digits: refused before (18 in total), within spec/EVALUATION.md section 2.
  CHECK(parse_epsilon("1234567890.123456789") == Ratio{1234567890123456789ULL, 1000000000});
  CHECK(parse_epsilon("0.100000000000000000000000") == Ratio{1, 10});  // trailing zeros
  CHECK(parse_epsilon("000000000000000000000.5") == Ratio{1, 2});      // leading zeros
  CHECK(parse_epsilon("123456789012345678.5") == Ratio{246913578024691357ULL, 2});
  CHECK(parse_epsilon("0.000000000000000001") == Ratio{1, 1000000000000000000ULL});
  // Within 18 + 18 digits but no fraction of 64-bit integers: refused with a reason.
  CHECK_THROWS_WITH_AS(parse_epsilon("999999999999999999.999999999999999999"),
                       doctest::Contains("64-bit"), Error);
  CHECK_THROWS_AS(parse_epsilon("1234567890123456789"), Error);  // 19 whole digits
}

TEST_CASE("Ratio to_decimal rounds up and is exact when the expansion ends") {
  CHECK(Ratio{1, 10}.to_decimal() == "0.1");
  CHECK(Ratio{1, 3}.to_decimal(4) == "0.3334");
  CHECK(Ratio{2, 3}.to_decimal(3) == "0.667");
  CHECK(Ratio{999999, 1000000}.to_decimal(3) == "1");
  CHECK(Ratio{5, 1}.to_decimal() == "5");
  CHECK(Ratio{1, 0}.to_decimal() == "inf");
}

TEST_CASE("coverage and achieved epsilon agree with brute force on random fronts") {
  SplitMix64 rng(20261122);
  for (std::size_t d : {1u, 2u, 3u, 4u}) {
    for (int round = 0; round < 30; ++round) {
      const std::size_t n = rng.uniform(0, 40), m = rng.uniform(1, 40);
      const std::uint64_t hi = round % 3 == 0 ? 5 : 1000;  // small ranges: many ties and zeros
      const Front s = random_front(rng, n, d, hi), r = random_front(rng, m, d, hi);
      const auto needs = brute_needs(s, r, d);
      for (const Ratio& e : kEpsilons) {
        std::vector<std::size_t> expected;
        for (std::size_t b = 0; b < needs.size(); ++b)
          if (e < needs[b]) expected.push_back(b);
        CAPTURE(d);
        CAPTURE(round);
        CHECK(uncovered_reference(view(s, d), view(r, d), e) == expected);
        CHECK(uncovered_reference(view(s, d), view(r, d), e, {.strict_dominance = true}) ==
              brute_strict_uncovered(s, r, d, e));
      }
      const auto result = evaluate_front(view(s, d), view(r, d), kEpsilons);
      Ratio worst{0, 1};
      for (const Ratio& e : needs)
        if (worst < e) worst = e;
      CHECK(result.achieved == worst);
      if (worst == Ratio{0, 1}) {
        CHECK(!result.worst_reference.has_value());
      } else {
        REQUIRE(result.worst_reference.has_value());
        CHECK(needs[*result.worst_reference] == worst);
      }
    }
  }
}

TEST_CASE("double costs agree with brute force on random fronts") {
  SplitMix64 rng(7);
  for (std::size_t d : {2u, 3u, 4u}) {
    for (int round = 0; round < 20; ++round) {
      const std::size_t n = rng.uniform(1, 30), m = rng.uniform(1, 30);
      std::vector<double> s(n * d), r(m * d);
      for (auto& v : s) v = static_cast<double>(rng.uniform(0, 1000)) / 8;
      for (auto& v : r) v = static_cast<double>(rng.uniform(0, 1000)) / 8;
      double achieved = 0;
      for (std::size_t b = 0; b < m; ++b) {
        double best = std::numeric_limits<double>::infinity();
        for (std::size_t a = 0; a < n; ++a) {
          double worst = 0;
          for (std::size_t i = 0; i < d; ++i) {
            const double p = s[a * d + i], q = r[b * d + i];
            const double e =
                p <= q ? 0 : (q == 0 ? std::numeric_limits<double>::infinity() : p / q - 1);
            worst = std::max(worst, e);
          }
          best = std::min(best, worst);
        }
        achieved = std::max(achieved, best);
      }
      const auto result = evaluate_front(FrontView<double>{s, d}, FrontView<double>{r, d}, {});
      if (std::isinf(achieved)) {
        CHECK(std::isinf(result.achieved_value));
      } else {
        CHECK(result.achieved_value == doctest::Approx(achieved).epsilon(1e-12));
      }
    }
  }
}

TEST_CASE("an exact front is the same multiset and covered at every epsilon") {
  const Front r = {1, 10, 3, 7, 5, 5, 10, 1};
  const Front s = {10, 1, 5, 5, 1, 10, 3, 7};  // shuffled
  const auto result = evaluate_front(view(s, 2), view(r, 2), kEpsilons);
  CHECK(result.same_multiset);
  CHECK(result.achieved == Ratio{0, 1});
  CHECK(result.dominated_by_reference.empty());
  for (const auto& c : result.coverage) CHECK(c.covered);
}

TEST_CASE("a missing extreme point is uncovered and is the worst reference vector") {
  const Front r = {1, 10, 3, 7, 5, 5, 10, 1};
  const Front s = {3, 7, 5, 5, 10, 1};
  const auto result = evaluate_front(view(s, 2), view(r, 2), kEpsilons);
  CHECK_FALSE(result.same_multiset);
  // (1,10) needs (3-1)/1 = 2 from (3,7).
  CHECK(result.achieved == Ratio{2, 1});
  CHECK(result.worst_reference == std::optional<std::size_t>{0});
  for (const auto& c : result.coverage) {
    CHECK_FALSE(c.covered);
    CHECK(c.uncovered == 1);
  }
}

TEST_CASE("a solution vector the reference strictly dominates is reported") {
  const Front r = {1, 10, 5, 5, 10, 1};
  const Front s = {1, 10, 6, 5, 5, 5, 10, 1, 1, 10};  // (6,5) dominated; a duplicate (1,10) is not
  const auto result = evaluate_front(view(s, 2), view(r, 2), kEpsilons);
  CHECK(result.dominated_by_reference == std::vector<std::size_t>{1});
  CHECK(result.achieved == Ratio{0, 1});
  CHECK_FALSE(result.same_multiset);
  CHECK_FALSE(result.coverage[0].covered);
  CHECK(result.coverage[1].covered);
}

TEST_CASE("a vector epsilon-dominated only at 0.1") {
  const Front r = {100, 200, 200, 100};
  const Front s = {110, 220, 200, 100};  // (110,220) = 1.1·(100,200)
  const auto result = evaluate_front(view(s, 2), view(r, 2), kEpsilons);
  CHECK(result.achieved == Ratio{1, 10});
  CHECK(result.achieved.to_decimal() == "0.1");
  CHECK_FALSE(result.coverage[1].covered);  // 0.01
  CHECK_FALSE(result.coverage[2].covered);  // 0.05
  CHECK(result.coverage[3].covered);        // 0.1
  CHECK(result.coverage[4].covered);        // 0.5
  // The paper's literal reading: at ε = 0.1, (110,220) equals (1+ε)·q, strict nowhere.
  const auto strict = evaluate_front(view(s, 2), view(r, 2), kEpsilons, {.strict_dominance = true});
  CHECK_FALSE(strict.coverage[3].covered);
  CHECK(strict.coverage[4].covered);
  CHECK(strict.achieved == Ratio{1, 10});  // the infimum, as documented
}

TEST_CASE("integer costs are compared exactly where double arithmetic would drift") {
  // (1 + 0.01)·100000000000000003 = 101000000000000003.03: p = ...003 is covered, ...004 not;
  // a double holds neither value exactly.
  const Ratio e = parse_epsilon("0.01");
  const Front r = {100000000000000003ULL};
  CHECK(uncovered_reference(view(Front{101000000000000003ULL}, 1), view(r, 1), e).empty());
  CHECK(uncovered_reference(view(Front{101000000000000004ULL}, 1), view(r, 1), e).size() == 1);
  const auto result = evaluate_front(view(Front{101000000000000004ULL}, 1), view(r, 1), {});
  CHECK(result.achieved == Ratio{1000000000000001ULL, 100000000000000003ULL});
}

TEST_CASE("a zero reference cost needs a zero solution cost") {
  const Front r = {0, 5};
  const auto none = evaluate_front(view(Front{1, 5}, 2), view(r, 2), kEpsilons);
  CHECK(none.achieved.is_infinite());
  CHECK(none.worst_reference == std::optional<std::size_t>{0});
  const auto some = evaluate_front(view(Front{0, 6}, 2), view(r, 2), kEpsilons);
  CHECK(some.achieved == Ratio{1, 5});
  const auto empty = evaluate_front(view(Front{}, 2), view(r, 2), kEpsilons);
  CHECK(empty.achieved.is_infinite());
  const auto nothing = evaluate_front(view(Front{}, 2), view(Front{}, 2), kEpsilons);
  CHECK(nothing.achieved == Ratio{0, 1});
  CHECK(nothing.same_multiset);
}

TEST_CASE("fronts of different dimensions are refused") {
  CHECK_THROWS_AS(evaluate_front(view(Front{1, 2}, 2), view(Front{1, 2, 3}, 3), kEpsilons), Error);
}
