// mosb_bench_eval: evaluate_front on large fronts (issue 11's target: a 1,000,000-vector
// 3-objective solution set against a 100,000-vector reference in seconds).
//
//   mosb_bench_eval [--quick]
//
// Reference: mutually non-dominated integer vectors (coordinates summing to a constant). Solution:
// each reference vector scaled up by a random factor in [1, 1.08) per coordinate, plus random
// vectors on a slightly higher plane, shuffled, to |S| vectors. Prints the time of one coverage
// test and of the whole evaluation (ε = 0, 0.01, 0.05, 0.1 and the achieved ε), for d = 2 and 3.
// Figures only; exit 1 only when a result is wrong (the achieved ε must be below 0.08).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

#include "mosb/eval.hpp"
#include "mosb/random.hpp"

using namespace mosb;
using Clock = std::chrono::steady_clock;

namespace {

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

constexpr std::uint64_t kSum = 30'000'000;

// A vector whose d coordinates sum to `sum`: d-1 sorted cut points in [0, sum].
void on_plane(SplitMix64& rng, std::size_t d, std::uint64_t sum, std::uint64_t* out) {
  std::vector<std::uint64_t> cuts(d - 1);
  for (auto& c : cuts) c = rng.uniform(0, sum);
  std::sort(cuts.begin(), cuts.end());
  std::uint64_t previous = 0;
  for (std::size_t i = 0; i + 1 < d; ++i) {
    out[i] = cuts[i] - previous + 1;  // +1: no zero costs
    previous = cuts[i];
  }
  out[d - 1] = sum - previous + 1;
}

int run(std::size_t d, std::size_t reference_size, std::size_t solution_size) {
  SplitMix64 rng(42 + d);
  std::vector<std::uint64_t> reference(reference_size * d), solution(solution_size * d);
  for (std::size_t k = 0; k < reference_size; ++k) on_plane(rng, d, kSum, &reference[k * d]);
  for (std::size_t k = 0; k < solution_size; ++k) {
    std::uint64_t* p = &solution[k * d];
    if (k < reference_size) {
      for (std::size_t i = 0; i < d; ++i)
        p[i] = reference[k * d + i] + reference[k * d + i] * rng.uniform(0, 79) / 1000;
    } else {
      on_plane(rng, d, kSum + kSum / 50, p);
    }
  }
  const FrontView<std::uint64_t> s{solution, d}, r{reference, d};

  auto start = Clock::now();
  const auto open = uncovered_reference(s, r, parse_epsilon("0.05"));
  const double one_test = seconds_since(start);

  const std::vector<Ratio> epsilons = {parse_epsilon("0"), parse_epsilon("0.01"),
                                       parse_epsilon("0.05"), parse_epsilon("0.1")};
  start = Clock::now();
  const auto result = evaluate_front(s, r, epsilons);
  const double whole = seconds_since(start);

  std::printf(
      "d=%zu |S|=%zu |R|=%zu: one coverage test (eps 0.05, %zu uncovered) %.3f s; "
      "evaluate_front %.3f s: achieved eps %s, covered at 0.1: %s, dominated by reference: "
      "%zu\n",
      d, solution_size, reference_size, open.size(), one_test, whole,
      result.achieved.to_decimal(9).c_str(), result.coverage[3].covered ? "yes" : "no",
      result.dominated_by_reference.size());
  if (!(result.achieved < parse_epsilon("0.08")) || !result.coverage[3].covered) {
    std::fprintf(stderr, "wrong result: every reference vector has a copy scaled by < 1.08\n");
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const std::size_t r = quick ? 10'000 : 100'000, s = quick ? 100'000 : 1'000'000;
  int status = 0;
  for (std::size_t d : {2u, 3u}) status |= run(d, r, s);
  return status;
}
