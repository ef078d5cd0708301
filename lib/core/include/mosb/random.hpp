// The random source of every mosb generator, specified bit for bit in spec/GENERATORS.md so that a
// seed gives the same instance on every platform and standard library.
#pragma once

#include <cstdint>

namespace mosb {

// SplitMix64 (Steele, Lea, Flood 2014).
class SplitMix64 {
 public:
  explicit constexpr SplitMix64(std::uint64_t seed) : state_(seed) {}

  constexpr std::uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ULL;
    return mix(state_);
  }

  // Uniform integer in [lo, hi] by rejection: draws below 2^64 mod r are redrawn, the rest taken
  // modulo r, so every value has exactly the same number of preimages.
  constexpr std::uint64_t uniform(std::uint64_t lo, std::uint64_t hi) {
    const std::uint64_t range = hi - lo + 1;
    if (range == 0) return next();                           // [0, 2^64 - 1]
    const std::uint64_t reject_below = (0 - range) % range;  // 2^64 mod range
    std::uint64_t x = next();
    while (x < reject_below) x = next();
    return lo + x % range;
  }

  static constexpr std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

 private:
  std::uint64_t state_;
};

// Stream `index` of a seed: independent streams let a generator draw objective j's costs without
// depending on how many objectives there are.
constexpr SplitMix64 stream(std::uint64_t seed, std::uint64_t index) {
  return SplitMix64(SplitMix64::mix(seed + 0x9E3779B97F4A7C15ULL * (index + 1)));
}

}  // namespace mosb
