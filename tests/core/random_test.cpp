#include "mosb/random.hpp"

#include <doctest/doctest.h>

#include <array>
#include <cstdlib>

using mosb::SplitMix64;

TEST_CASE("SplitMix64 matches the reference sequence of spec/GENERATORS.md") {
  SplitMix64 rng(0);
  CHECK(rng.next() == 0xE220A8397B1DCDAFULL);
  CHECK(rng.next() == 0x6E789E6AA1B965F4ULL);
  CHECK(rng.next() == 0x06C45D188009454FULL);
}

TEST_CASE("uniform draws stay in range and hit every value about equally") {
  SplitMix64 rng(42);
  std::array<int, 10> counts{};
  constexpr int kDraws = 100000;
  for (int i = 0; i < kDraws; ++i) {
    auto x = rng.uniform(1, 10);
    REQUIRE(x >= 1);
    REQUIRE(x <= 10);
    ++counts[x - 1];
  }
  // Each count is Binomial(100000, 0.1): sd ~ 95, so +-600 is over 6 sd.
  for (int c : counts) CHECK(std::abs(c - kDraws / 10) < 600);
}

TEST_CASE("uniform rejects the biased low draws") {
  // For r = 3, 2^64 mod 3 = 1: the draw 0 must be rejected. A state that yields 0 first is hard to
  // construct, so check the threshold arithmetic the generator uses instead.
  const std::uint64_t r = 3;
  CHECK((0 - r) % r == 1);
  const std::uint64_t r2 = 10;
  CHECK((0 - r2) % r2 == 6);  // 2^64 = 18446744073709551616 ends in 6
}

TEST_CASE("streams of one seed differ, and are reproducible") {
  auto a = mosb::stream(7, 0), b = mosb::stream(7, 1), a2 = mosb::stream(7, 0);
  const auto x = a.next();
  CHECK(x != b.next());
  CHECK(x == a2.next());
}
