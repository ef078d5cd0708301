// mosb_bench_eval: evaluate_front on large fronts (issue 11's target: a 1,000,000-vector
// 3-objective solution set against a 100,000-vector reference in seconds; issue 44's: 1,000,000
// against 1,000,000 in 8 objectives under 60 s and 2 GB).
//
//   mosb_bench_eval [--quick]
//   mosb_bench_eval --scaling [MAX_N [NAIVE_MAX_N [D]]]
//   mosb_bench_eval --small [D]
//
// Reference: mutually non-dominated integer vectors (coordinates summing to a constant). Solution:
// each reference vector scaled up by a random factor in [1, 1.08) per coordinate, plus random
// vectors on a slightly higher plane, shuffled, to |S| vectors. Prints the time of one coverage
// test and of the whole evaluation (ε = 0, 0.01, 0.05, 0.1 and the achieved ε), for d = 2 and 3.
// Figures only; exit 1 only when a result is wrong (the achieved ε must be below 0.08).
//
// --scaling (issue 44): for d = 2, 3, 5, 8 (or D alone) and n = 10^4, 10^5, 10^6 (up to MAX_N), a
// reference of n vectors on the plane "sum of costs = constant" and a solution holding each of them
// + 1 in one coordinate (the two fronts are mutually non-dominated); evaluate_front at ε = 0, 0.01,
// 0.1 as `mosb eval --eps 0,0.01,0.1` runs it. Each case runs in a child process: its wall time and
// peak RSS (fronts included). Up to NAIVE_MAX_N (default 10^4) the naive definitions (a scan of
// one front per vector of the other) also run, in another child, and must give the same results.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
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

// Issue 44's fronts: the reference on the plane, the solution each reference vector + 1 in the
// coordinate k mod d.
struct Fronts {
  std::vector<std::uint64_t> reference, solution;
};

Fronts plane_fronts(std::size_t d, std::size_t n) {
  SplitMix64 rng(44 + d);
  Fronts f{std::vector<std::uint64_t>(n * d), {}};
  for (std::size_t k = 0; k < n; ++k) on_plane(rng, d, kSum, &f.reference[k * d]);
  f.solution = f.reference;
  for (std::size_t k = 0; k < n; ++k) ++f.solution[k * d + k % d];
  return f;
}

const std::vector<Ratio> kScalingEpsilons = {parse_epsilon("0"), parse_epsilon("0.01"),
                                             parse_epsilon("0.1")};

// What both algorithms report, as one line: coverage per ε, the achieved ε, the dominated count.
std::string summary(const FrontEvaluation& e) {
  std::string text;
  for (const auto& c : e.coverage)
    text += (c.covered ? "y" : "n") + std::to_string(c.uncovered) + " ";
  return text + e.achieved.to_decimal(9) + " " + std::to_string(e.dominated_by_reference.size());
}

// The definitions of spec/EVALUATION.md §1 for integer costs, each by a scan of the other front.
__extension__ typedef unsigned __int128 u128;  // NOLINT(modernize-use-using)

bool naive_covers(const std::uint64_t* p, const std::uint64_t* q, std::size_t d, Ratio e) {
  for (std::size_t i = 0; i < d; ++i)
    if (static_cast<u128>(e.den) * p[i] > static_cast<u128>(e.den + e.num) * q[i]) return false;
  return true;
}

FrontEvaluation naive_evaluate(FrontView<std::uint64_t> s, FrontView<std::uint64_t> r) {
  const std::size_t d = r.dimension;
  FrontEvaluation e;
  for (const Ratio& eps : kScalingEpsilons) {
    EpsilonCoverage c{eps, false, 0, 0};
    for (std::size_t b = 0; b < r.size(); ++b) {
      bool covered = false;
      for (std::size_t a = 0; a < s.size() && !covered; ++a)
        covered =
            eps.num == 0 ? std::equal(s[a], s[a] + d, r[b]) : naive_covers(s[a], r[b], d, eps);
      c.uncovered += covered ? 0 : 1;
    }
    c.covered = c.uncovered == 0;
    e.coverage.push_back(c);
  }
  Ratio achieved{0, 1};
  for (std::size_t b = 0; b < r.size(); ++b) {
    Ratio best{1, 0};
    for (std::size_t a = 0; a < s.size(); ++a) {
      Ratio worst{0, 1};
      for (std::size_t i = 0; i < d && worst < best; ++i)
        if (s[a][i] > r[b][i])
          worst = std::max(worst, r[b][i] == 0 ? Ratio{1, 0} : Ratio{s[a][i] - r[b][i], r[b][i]});
      best = std::min(best, worst);
    }
    achieved = std::max(achieved, best);
  }
  e.achieved = achieved;  // unreduced: summary() prints its value only
  for (std::size_t a = 0; a < s.size(); ++a) {
    bool dominated = false, equal = false;
    for (std::size_t b = 0; b < r.size(); ++b) {
      dominated = dominated || naive_covers(r[b], s[a], d, {0, 1});
      equal = equal || std::equal(s[a], s[a] + d, r[b]);
    }
    if (dominated && !equal) e.dominated_by_reference.push_back(a);
  }
  return e;
}

// Runs `work` in a child; its wall time in seconds and peak RSS in MiB. The child writes its
// summary line to `summary_out` through a pipe.
struct ChildRun {
  double seconds = 0, peak_mib = 0;
  std::string summary;
};

template <class Work>
ChildRun in_child(Work work) {
  int fds[2];
  if (pipe(fds) != 0) std::exit(1);
  const auto start = Clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const std::string line = work();
    const bool written =
        write(fds[1], line.data(), line.size()) == static_cast<ssize_t>(line.size());
    _exit(written ? 0 : 1);
  }
  close(fds[1]);
  ChildRun run;
  char buffer[512];
  for (ssize_t got; (got = read(fds[0], buffer, sizeof buffer)) > 0;)
    run.summary.append(buffer, static_cast<std::size_t>(got));
  close(fds[0]);
  int status = 0;
  struct rusage usage {};
  wait4(pid, &status, 0, &usage);
  run.seconds = seconds_since(start);
  run.peak_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::fprintf(stderr, "benchmark child failed\n");
    std::exit(1);
  }
  return run;
}

int scaling(std::size_t max_n, std::size_t naive_max_n, std::size_t only_d) {
  std::printf(
      "| d | n | evaluate_front | peak RSS | naive | results (per eps: covered, uncovered; "
      "achieved eps; dominated) |\n");
  std::printf("|---|---|---|---|---|---|\n");
  int status = 0;
  for (std::size_t d : {2u, 3u, 5u, 8u}) {
    if (only_d != 0 && d != only_d) continue;
    for (std::size_t n = 10'000; n <= max_n; n *= 10) {
      // The fronts are generated before the clock starts: the time is the evaluation's.
      double eval_seconds = 0;
      const ChildRun fast = in_child([&] {
        const Fronts f = plane_fronts(d, n);
        const auto start = Clock::now();
        const auto e = evaluate_front(FrontView<std::uint64_t>{f.solution, d},
                                      FrontView<std::uint64_t>{f.reference, d}, kScalingEpsilons);
        return std::to_string(seconds_since(start)) + " " + summary(e);
      });
      const std::size_t space = fast.summary.find(' ');
      eval_seconds = std::strtod(fast.summary.c_str(), nullptr);
      const std::string result = fast.summary.substr(space + 1);
      std::string naive = "-";
      if (n <= naive_max_n) {
        const ChildRun slow = in_child([&] {
          const Fronts f = plane_fronts(d, n);
          const auto start = Clock::now();
          const auto e = naive_evaluate(FrontView<std::uint64_t>{f.solution, d},
                                        FrontView<std::uint64_t>{f.reference, d});
          return std::to_string(seconds_since(start)) + " " + summary(e);
        });
        naive = std::to_string(std::strtod(slow.summary.c_str(), nullptr)) + " s";
        if (slow.summary.substr(slow.summary.find(' ') + 1) != result) {
          std::fprintf(stderr, "d=%zu n=%zu: evaluate_front gives %s, the definitions %s\n", d, n,
                       result.c_str(), slow.summary.c_str());
          status = 1;
        }
      }
      std::printf("| %zu | %zu | %.3f s | %.0f MiB | %s | %s |\n", d, n, eval_seconds,
                  fast.peak_mib, naive.c_str(), result.c_str());
      std::fflush(stdout);
    }
  }
  return status;
}

// --small: many queries with small fronts, as a real eval has them (10,000 pairs of 8 to 64
// vectors, the same plane fronts): the per-call cost of the structures, not their scaling.
int small_fronts(std::size_t only_d) {
  for (std::size_t d : {2u, 3u, 5u, 8u}) {
    if (only_d != 0 && d != only_d) continue;
    std::vector<Fronts> pairs;
    for (std::size_t k = 0; k < 10'000; ++k) pairs.push_back(plane_fronts(d, 8 + k % 57));
    const auto start = Clock::now();
    std::size_t uncovered = 0;
    for (const Fronts& f : pairs)
      uncovered += evaluate_front(FrontView<std::uint64_t>{f.solution, d},
                                  FrontView<std::uint64_t>{f.reference, d}, kScalingEpsilons)
                       .coverage[1]
                       .uncovered;
    std::printf("d=%zu: 10,000 evaluations of 8-64 vectors: %.3f s (%zu uncovered at 0.01)\n", d,
                seconds_since(start), uncovered);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::strcmp(argv[1], "--small") == 0)
    return small_fronts(argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 0);
  if (argc > 1 && std::strcmp(argv[1], "--scaling") == 0)
    return scaling(argc > 2 ? std::strtoull(argv[2], nullptr, 10) : 1'000'000,
                   argc > 3 ? std::strtoull(argv[3], nullptr, 10) : 10'000,
                   argc > 4 ? std::strtoull(argv[4], nullptr, 10) : 0);
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const std::size_t r = quick ? 10'000 : 100'000, s = quick ? 100'000 : 1'000'000;
  int status = 0;
  for (std::size_t d : {2u, 3u}) status |= run(d, r, s);
  return status;
}
