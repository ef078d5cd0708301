#include "mosb/eval.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
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

TEST_CASE("parse_epsilon says why: out of range, negative, not a number, an exponent") {
  // Issue 33 §6: 1e400 is a number too large for an ε, not "not a number".
  const auto why = [](const char* text) {
    try {
      parse_epsilon(text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  for (const char* text : {"1e400", "1e18", "inf", "1234567890123456789", "1e-400",
                           "0.0000000000000000001", "999999999999999999.999999999999999999"}) {
    CAPTURE(text);
    CHECK(why(text).find("out of range") != std::string::npos);
  }
  CHECK(why("-1").find("negative") != std::string::npos);
  CHECK(why("-1e400").find("negative") != std::string::npos);
  for (const char* text : {"abc", "", "nan", "0.1.2", "0x10"}) {
    CAPTURE(text);
    CHECK(why(text).find("not a number") != std::string::npos);
  }
  CHECK(why("1e-3").find("without an exponent") != std::string::npos);
  CHECK(why("0.1234567890123456789") ==
        "invalid epsilon '0.1234567890123456789': more than 18 digits after the point");
  CHECK(why("1e400") ==
        "invalid epsilon '1e400': out of range: an epsilon is below 10^18 and a "
        "multiple of 10^-18");
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

namespace {

// The coverage test of spec/EVALUATION.md §2 for double costs, written from the definition: p
// ε-covers q iff p_i ≤ (1+ε)·q_i for every i, 1+ε rounded to a double, then the product; at ε =
// +infinity every q_i > 0 is met, a q_i = 0 only by p_i = 0.
bool brute_covers(const double* p, const double* q, std::size_t d, double e) {
  for (std::size_t i = 0; i < d; ++i) {
    const bool met = std::isinf(e) ? (q[i] > 0 || p[i] == 0) : p[i] <= (1.0 + e) * q[i];
    if (!met) return false;
  }
  return true;
}

std::size_t brute_uncovered(const std::vector<double>& s, const std::vector<double>& r,
                            std::size_t d, double e) {
  std::size_t uncovered = 0;
  for (std::size_t b = 0; b < r.size() / d; ++b) {
    bool covered = false;
    for (std::size_t a = 0; a < s.size() / d && !covered; ++a)
      covered = brute_covers(&s[a * d], &r[b * d], d, e);
    uncovered += covered ? 0 : 1;
  }
  return uncovered;
}

// A cost in [0, 1000) with every bit of its mantissa used (of a float for f32 columns); zero one
// time in ten.
double random_cost(SplitMix64& rng, bool f32) {
  if (rng.uniform(0, 9) == 0) return 0.0;
  const double v = static_cast<double>(rng.uniform(0, (std::uint64_t{1} << 53) - 1)) /
                   static_cast<double>(std::uint64_t{1} << 43);
  return f32 ? static_cast<double>(static_cast<float>(v)) : v;
}

// A value near `v` as the two solvers of one benchmark differ: equal, 1 to 3 units in the last
// place above or below (of a float for f32 columns), a relative 1e-6 off, zero, or another value.
double nearby(SplitMix64& rng, double v, bool f32) {
  const auto step = [&](double x, bool up, std::uint64_t k) {
    for (; k > 0; --k)
      x = f32 ? static_cast<double>(std::nextafter(static_cast<float>(x), up ? 1e30f : 0.0f))
              : std::nextafter(x, up ? 1e300 : 0.0);
    return x;
  };
  switch (rng.uniform(0, 5)) {
    case 0:
      return v;
    case 1:
      return step(v, true, rng.uniform(1, 3));
    case 2:
      return step(v, false, rng.uniform(1, 3));
    case 3:
      return f32 ? static_cast<double>(static_cast<float>(v * (1 + 1e-6))) : v * (1 + 1e-6);
    case 4:
      return 0.0;
    default:
      return random_cost(rng, f32);
  }
}

}  // namespace

// The brute-force definition of spec/EVALUATION.md §2 for double costs: the comparison holds
// for a coordinate when fl(g·q) ≥ p, g = fl(1+ε); a coordinate needs the smallest such double g
// (found here by stepping one double at a time from p/q, a few steps at most); the achieved ε is
// g − 1 for the largest over q of the smallest over p of the largest over i of those needs.
double brute_achieved(const std::vector<double>& s, const std::vector<double>& r, std::size_t d) {
  const auto need = [](double p, double q) {
    if (p <= q) return 1.0;
    if (q == 0) return std::numeric_limits<double>::infinity();
    double g = std::max(1.0, p / q);
    while (!(g * q >= p)) g = std::nextafter(g, 2 * g);
    while (g > 1 && std::nextafter(g, 0.0) * q >= p) g = std::nextafter(g, 0.0);
    return g;
  };
  double worst = 1;
  for (std::size_t b = 0; b < r.size() / d; ++b) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < s.size() / d; ++a) {
      double g = 1;
      for (std::size_t i = 0; i < d; ++i) g = std::max(g, need(s[a * d + i], r[b * d + i]));
      best = std::min(best, g);
    }
    worst = std::max(worst, best);
  }
  return worst - 1;
}

TEST_CASE("double costs: the achieved epsilon agrees with brute force, and is found fast") {
  // Issue 33 §1: one solver value an ulp above the reference's stepped ε an ulp of ε at a time
  // (minutes on a real EMOA* front). On random f64 and f32 fronts, values 1-3 ulps apart and
  // zeros among them, every call must return within a second and give the ε the definition
  // gives: covered at a requested ε exactly when fl(1+ε) ≥ 1 + the achieved ε, so covered at the
  // achieved ε and not at the ε of the double below 1 + it (spec/EVALUATION.md §2).
  SplitMix64 rng(33);
  for (const bool f32 : {false, true})
    for (std::size_t d : {1u, 2u, 3u, 4u})
      for (int round = 0; round < 12; ++round) {
        const std::size_t m = round == 11 ? 300 : rng.uniform(1, 40);  // 300: the sampling path
        std::vector<double> r(m * d), s;
        for (auto& v : r) v = random_cost(rng, f32);
        for (std::size_t b = 0; b < m; ++b)
          if (rng.uniform(0, 5) != 0)
            for (std::size_t i = 0; i < d; ++i) s.push_back(nearby(rng, r[b * d + i], f32));
        const auto start = std::chrono::steady_clock::now();
        const auto result =
            evaluate_front(FrontView<double>{s, d}, FrontView<double>{r, d}, kEpsilons);
        const auto seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        CAPTURE(f32);
        CAPTURE(d);
        CAPTURE(round);
        CHECK(seconds < 1.0);
        const double achieved = result.achieved_value;
        CHECK(achieved == brute_achieved(s, r, d));
        // Infinite when no ε covers (a q_i = 0 no p meets with p_i = 0, or an empty S).
        if (!std::isinf(achieved)) CHECK(brute_uncovered(s, r, d, achieved) == 0);
        if (achieved > 0)
          CHECK(brute_uncovered(s, r, d, std::nextafter(1 + achieved, 0.0) - 1) > 0);
        for (std::size_t k = 1; k < kEpsilons.size(); ++k) {  // ε = 0 is the multiset test
          const double e = kEpsilons[k].to_double();
          CHECK(result.coverage[k].uncovered == brute_uncovered(s, r, d, e));
          CHECK(result.coverage[k].covered == (1 + e >= 1 + achieved));
        }
      }
}

TEST_CASE("a solver value ulps above the reference's needs a tiny epsilon, found at once") {
  // The real case: EMOA* 43.88584 against NAMOA* 43.88583999999999 (two doubles apart), and
  // one ulp apart.
  const double below = 43.88583999999999;
  for (const double above : {43.88584, std::nextafter(below, 100.0)}) {
    CAPTURE(above);
    const std::vector<double> s = {above, 7.5}, r = {below, 7.5};
    const auto start = std::chrono::steady_clock::now();
    const auto result = evaluate_front(FrontView<double>{s, 2}, FrontView<double>{r, 2}, kEpsilons);
    CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(1));
    CHECK(result.achieved_value > 0);
    CHECK(result.achieved_value < 1e-15);
    CHECK((1.0 + result.achieved_value) * below >= above);
    CHECK(std::nextafter(1.0 + result.achieved_value, 0.0) * below < above);
    CHECK_FALSE(result.coverage[0].covered);  // ε = 0: not the same multiset
    CHECK(result.coverage[0].uncovered == 1);
    CHECK(result.coverage[0].extra == 1);
    CHECK(result.coverage[1].covered);
    CHECK(achieved_epsilon_text(result, false) == "0.000000001");  // never "0" for a positive ε
    const auto back = evaluate_front(FrontView<double>{r, 2}, FrontView<double>{s, 2}, kEpsilons);
    CHECK(back.achieved_value == 0);
  }
}

// Issue 44: the front index answers the coverage, dominance and need queries for d >= 4. Against
// the definitions, in every dimension 2..8, on fronts built to hit the edge cases: equal vectors,
// vectors the reference dominates, vectors exactly at (1+ε)·q and one step either side of it
// (integer and double), zeros, and values near 2^64 whose (1+ε)·q does not fit in 64 bits.
namespace {

const std::vector<Ratio> kPropertyEpsilons = {{0, 1}, {1, 100}, {1, 10}, {1, 2}, {7, 3}};

// The ε tested per coordinate, by the index of the ε in kPropertyEpsilons.
std::uint64_t integer_bound(std::uint64_t q, const Ratio& e) {
  __extension__ typedef unsigned __int128 u128;
  const u128 b = q + static_cast<u128>(e.num) * q / e.den;
  return b > std::numeric_limits<std::uint64_t>::max() ? std::numeric_limits<std::uint64_t>::max()
                                                       : static_cast<std::uint64_t>(b);
}

// A reference near the plane "sum of costs = d·hi/2", with duplicates and a few dominated
// vectors; and a solution of vectors derived from the reference's (copies, the (1+ε)·q boundary
// and its neighbours, dominated and dominating ones) and random ones.
template <class T, class Near, class Random>
void random_fronts(SplitMix64& rng, std::size_t d, std::size_t m, std::vector<T>& r,
                   std::vector<T>& s, Near near, Random random) {
  for (std::size_t b = 0; b < m; ++b) {
    if (b > 0 && rng.uniform(0, 9) == 0) {  // a duplicate or a dominated copy of an earlier one
      const std::size_t from = rng.uniform(0, b - 1);
      for (std::size_t i = 0; i < d; ++i) r.push_back(r[from * d + i]);
      if (rng.uniform(0, 1) == 0) r.back() = near(r.back(), 1, 1);
      continue;
    }
    for (std::size_t i = 0; i < d; ++i) r.push_back(random());
  }
  const std::size_t n = rng.uniform(0, 2 * m);
  for (std::size_t a = 0; a < n; ++a) {
    if (m == 0 || rng.uniform(0, 4) == 0) {
      for (std::size_t i = 0; i < d; ++i) s.push_back(random());
      continue;
    }
    const std::size_t b = rng.uniform(0, m - 1);
    // 0: a copy; 1: at or just inside (1+ε)·q for one ε, now and then just outside; 2, 3: a mix.
    const auto kind = rng.uniform(0, 3);
    const auto eps = rng.uniform(0, kPropertyEpsilons.size() - 1);
    for (std::size_t i = 0; i < d; ++i) {
      const T q = r[b * d + i];
      const auto how =
          kind == 1 ? (rng.uniform(0, 2 * d) == 0 ? 1 : rng.uniform(0, 1) * 2) : rng.uniform(0, 4);
      s.push_back(kind == 0 ? q : near(q, how, kind == 1 ? eps : rng.uniform(0, 4)));
    }
  }
}

// `near(q, how, k)` for the k-th ε: how 0 gives (1+ε)·q as rounded, 1 the value just above it,
// 2 the value just below it (not below q), 3 a value near q, 4 a random one.

// Integers: mode 0 small values (ties, zeros), 1 mid-range, 2 near 2^64.
void integer_fronts(SplitMix64& rng, std::size_t d, std::size_t m, int mode, Front& r, Front& s) {
  const std::uint64_t lo = mode == 2 ? std::uint64_t{1} << 63 : 0;
  const std::uint64_t hi = mode == 0 ? 6 : (mode == 1 ? 100'000 : UINT64_MAX);
  const auto random = [&] { return rng.uniform(lo, hi); };
  const auto near = [&](std::uint64_t q, std::uint64_t how, std::uint64_t k) -> std::uint64_t {
    const std::uint64_t bound = integer_bound(q, kPropertyEpsilons[k]);
    switch (how) {
      case 0:
        return bound;
      case 1:
        return bound == UINT64_MAX ? bound : bound + 1;
      case 2:
        return bound > q ? bound - 1 : bound;
      case 3:
        return rng.uniform(0, 1) == 0 ? q - (q > lo ? 1 : 0) : q + (q < hi ? 1 : 0);
      default:
        return random();
    }
  };
  random_fronts<std::uint64_t>(rng, d, m, r, s, near, random);
}

// Doubles (f64, or f32 values): the rounded (1+ε)·q and the doubles next to it, or nearby().
void double_fronts(SplitMix64& rng, std::size_t d, std::size_t m, bool f32, std::vector<double>& r,
                   std::vector<double>& s) {
  const auto random = [&] { return random_cost(rng, f32); };
  const auto near = [&](double q, std::uint64_t how, std::uint64_t k) {
    const double bound = (1.0 + kPropertyEpsilons[k].to_double()) * q;
    if (how == 0) return bound;
    if (how == 1) return std::nextafter(bound, 1e300);
    if (how == 2) return std::max(q, std::nextafter(bound, 0.0));
    return how == 3 ? nearby(rng, q, f32) : random();
  };
  random_fronts<double>(rng, d, m, r, s, near, random);
}

// The definitions for both types: p ε-covers q (weakly; strictly: and differs from (1+ε)·q),
// with (1+ε)·q compared exactly for integers (den·p ≤ (den+num)·q in 128 bits) and rounded as
// spec/EVALUATION.md §2 says for doubles.
int brute_sign(std::uint64_t p, std::uint64_t q, const Ratio& e) {
  __extension__ typedef unsigned __int128 u128;
  const u128 lhs = static_cast<u128>(e.den) * p, rhs = static_cast<u128>(e.den + e.num) * q;
  return lhs < rhs ? -1 : (lhs == rhs ? 0 : 1);
}
int brute_sign(double p, double q, const Ratio& e) {
  const double t = (1.0 + e.to_double()) * q;
  return p < t ? -1 : (p == t ? 0 : 1);
}

template <class T>
std::vector<std::size_t> brute_uncovered_at(const std::vector<T>& s, const std::vector<T>& r,
                                            std::size_t d, const Ratio& e, bool strict) {
  std::vector<std::size_t> out;
  for (std::size_t b = 0; b < r.size() / d; ++b) {
    bool covered = false;
    for (std::size_t a = 0; a < s.size() / d && !covered; ++a) {
      bool all = true, some = false;
      for (std::size_t i = 0; i < d; ++i) {
        const int sign = brute_sign(s[a * d + i], r[b * d + i], e);
        all = all && sign <= 0;
        some = some || sign < 0;
      }
      covered = all && (some || !strict);
    }
    if (!covered) out.push_back(b);
  }
  return out;
}

// The achieved ε for doubles by the definition of spec/EVALUATION.md §2, each coordinate's need
// (the smallest double g ≥ 1 with fl(g·q) ≥ p) by bisection over the bit patterns of the doubles
// from 1 to +infinity, ordered as their values: brute_achieved's stepping is too slow for values
// whose ratio is far from the need.
double bisected_achieved(const std::vector<double>& s, const std::vector<double>& r,
                         std::size_t d) {
  const auto need = [](double p, double q) {
    if (p <= q) return 1.0;
    if (q == 0) return std::numeric_limits<double>::infinity();
    std::uint64_t lo = std::bit_cast<std::uint64_t>(1.0),  // g = 1 does not hold (p > q)
        hi = std::bit_cast<std::uint64_t>(std::numeric_limits<double>::infinity());
    while (hi - lo > 1) {
      const std::uint64_t mid = lo + (hi - lo) / 2;
      (std::bit_cast<double>(mid) * q >= p ? hi : lo) = mid;
    }
    return std::bit_cast<double>(hi);
  };
  double worst = 1;
  for (std::size_t b = 0; b < r.size() / d; ++b) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < s.size() / d; ++a) {
      double g = 1;
      for (std::size_t i = 0; i < d; ++i) g = std::max(g, need(s[a * d + i], r[b * d + i]));
      best = std::min(best, g);
    }
    worst = std::max(worst, best);
  }
  return worst - 1;
}

// Solution vectors some reference vector is ≤ and no reference vector equals.
template <class T>
std::vector<std::size_t> brute_dominated(const std::vector<T>& s, const std::vector<T>& r,
                                         std::size_t d) {
  std::vector<std::size_t> out;
  for (std::size_t a = 0; a < s.size() / d; ++a) {
    bool below = false, equal = false;
    for (std::size_t b = 0; b < r.size() / d; ++b) {
      bool le = true, eq = true;
      for (std::size_t i = 0; i < d; ++i) {
        le = le && r[b * d + i] <= s[a * d + i];
        eq = eq && r[b * d + i] == s[a * d + i];
      }
      below = below || le;
      equal = equal || eq;
    }
    if (below && !equal) out.push_back(a);
  }
  return out;
}

template <class T>
void check_against_definitions(const std::vector<T>& s, const std::vector<T>& r, std::size_t d) {
  const FrontView<T> sv{s, d}, rv{r, d};
  for (const Ratio& e : kPropertyEpsilons) {
    CAPTURE(e.num);
    CAPTURE(e.den);
    CHECK(uncovered_reference(sv, rv, e) == brute_uncovered_at(s, r, d, e, false));
    if (e.num > 0)
      CHECK(uncovered_reference(sv, rv, e, {.strict_dominance = true}) ==
            brute_uncovered_at(s, r, d, e, true));
  }
  for (const bool strict : {false, true}) {
    const auto result = evaluate_front(sv, rv, kPropertyEpsilons, {.strict_dominance = strict});
    CHECK(result.dominated_by_reference == brute_dominated(s, r, d));
    for (std::size_t k = 1; k < kPropertyEpsilons.size(); ++k)
      CHECK(result.coverage[k].uncovered ==
            brute_uncovered_at(s, r, d, kPropertyEpsilons[k], strict).size());
    if constexpr (std::is_same_v<T, std::uint64_t>) {
      const auto needs = brute_needs(s, r, d);
      Ratio worst{0, 1};
      for (const Ratio& e : needs)
        if (worst < e) worst = e;
      CHECK(result.achieved == worst);
      if (result.worst_reference) CHECK(needs[*result.worst_reference] == worst);
    } else {
      // g − 1 is exact up to g = 2^53; beyond, the library's ε is the first whose 1 + ε is g.
      const double achieved = bisected_achieved(s, r, d);
      if (achieved < 0x1p52 || std::isinf(achieved)) CHECK(result.achieved_value == achieved);
    }
    CHECK(result.worst_reference.has_value() == (result.achieved_value > 0));
  }
}

}  // namespace

TEST_CASE(
    "every dimension 2..8: coverage, dominance and the achieved epsilon are the definitions'") {
  SplitMix64 rng(44);
  std::size_t found_uncovered = 0, found_dominated = 0;
  for (std::size_t d = 2; d <= 8; ++d) {
    for (int round = 0; round < 24; ++round) {
      // Mostly small fronts (every branch often), some large enough for a deep index.
      const std::size_t m = round % 6 == 5 ? rng.uniform(150, 400) : rng.uniform(0, 40);
      CAPTURE(d);
      CAPTURE(round);
      if (round % 2 == 0) {
        Front r, s;
        integer_fronts(rng, d, m, round / 2 % 3, r, s);
        check_against_definitions(s, r, d);
        found_uncovered += brute_uncovered_at(s, r, d, {1, 10}, false).size();
        found_dominated += brute_dominated(s, r, d).size();
      } else {
        std::vector<double> r, s;
        double_fronts(rng, d, m, round % 4 == 3, r, s);
        check_against_definitions(s, r, d);
      }
    }
  }
  CHECK(found_uncovered > 100);  // both answers exercised
  CHECK(found_dominated > 100);
}
