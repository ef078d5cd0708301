// mosb run's solver-output parser (spec/RUN.md §3): a front of VECTORS d-vectors (default
// 1,000,000 vectors of 3 integer costs below 10^7, the deterministic text a solver would print)
// parsed by parse_protocol_front; prints the bytes, the best of REPEATS runs and MB/s.
//
//     build/release/tests/bench/mosb_bench_run [VECTORS] [REPEATS]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "mosb/solver_protocol.hpp"

int main(int argc, char** argv) {
  const std::size_t vectors = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 5;
  constexpr std::size_t d = 3;
  std::mt19937_64 random(1);
  std::uniform_int_distribution<std::uint64_t> cost(0, 9999999);
  std::string text;
  for (std::size_t v = 0; v < vectors; ++v) {
    for (std::size_t k = 0; k < d; ++k) text += (k ? " " : "") + std::to_string(cost(random));
    text += '\n';
  }
  double best = 1e300;
  std::uint64_t parsed = 0;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const auto front = mosb::parse_protocol_front(text, d, "bench");
    const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
    best = std::min(best, took.count());
    parsed = front.vectors;
  }
  std::printf("front: %llu vectors of %zu values, %zu bytes; best of %d: %.4f s, %.1f MB/s\n",
              static_cast<unsigned long long>(parsed), d, text.size(), repeats, best,
              static_cast<double>(text.size()) / best / 1e6);
  return parsed == vectors ? 0 : 1;
}
