// mosb_bench_solutions: `mosb solutions verify --instance` on large fronts (issue 20's target:
// 1,000,000 3-objective vectors verified in under 10 s).
//
//   mosb_bench_solutions DIR [SIZE...]     (default sizes 100000 1000000)
//
// Writes DIR/grid.mosb (a 3x3 grid, 3 objectives stored as u32, query set `default` of one query)
// and, per size n and d = 2, 3, DIR/front-dD-N.sol.mosb: one solved query whose front is n
// distinct vectors whose coordinates sum to a constant, so mutually non-dominated, in random order.
// Then times SolutionReader::open + verify_solutions (what `mosb solutions verify --instance`
// does) on each file. The files stay in DIR, for timing the CLI (BENCHMARKS.md). Exit 1 when a
// front is reported as not verifying.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "mosb/converters/grid_generator.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/random.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_verify.hpp"

using namespace mosb;
using Clock = std::chrono::steady_clock;

namespace {

// n distinct vectors of d coordinates summing to 3n (d = 2: (k, 3n - k) for distinct k).
std::vector<double> plane_front(std::size_t n, std::size_t d, std::uint64_t seed) {
  SplitMix64 rng(seed);
  const std::uint64_t sum = 3 * n;
  std::vector<std::vector<std::uint64_t>> vectors;
  while (vectors.size() < n) {
    while (vectors.size() < n) {
      std::vector<std::uint64_t> v(d);
      std::uint64_t left = sum;
      for (std::size_t i = 0; i + 1 < d; ++i) left -= v[i] = rng.uniform(0, left);
      v[d - 1] = left;
      vectors.push_back(std::move(v));
    }
    std::sort(vectors.begin(), vectors.end());
    vectors.erase(std::unique(vectors.begin(), vectors.end()), vectors.end());
  }
  for (std::size_t k = n - 1; k > 0; --k) std::swap(vectors[k], vectors[rng.uniform(0, k)]);
  std::vector<double> costs;
  for (const auto& v : vectors) costs.insert(costs.end(), v.begin(), v.end());
  return costs;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: mosb_bench_solutions DIR [SIZE...]\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  std::vector<std::size_t> sizes;
  for (int i = 2; i < argc; ++i) sizes.push_back(std::stoull(argv[i]));
  if (sizes.empty()) sizes = {100'000, 1'000'000};
  std::filesystem::create_directories(dir);
  auto grid = converters::generate_grid({3, 3, 3, 1, 1, 10});
  for (auto& c : grid.costs) c.forced_type = format::ElementType::u32;
  grid.queries = {{"default", {{0, 8}}}};
  write_graph(grid, dir / "grid.mosb");
  const auto instance = GraphReader::open(dir / "grid.mosb", VerifyLevel::full);
  int status = 0;
  std::printf("%-10s %2s %12s\n", "vectors", "d", "verify (s)");
  for (const std::size_t n : sizes)
    for (std::size_t d = 2; d <= 3; ++d) {
      const auto path =
          dir / ("front-d" + std::to_string(d) + "-" + std::to_string(n) + ".sol.mosb");
      SolutionWriter writer(instance, "Grid_" + std::to_string(d));
      writer.set_query(0, QueryStatus::solved, plane_front(n, d, 7 * n + d));
      writer.write(path);
      const auto start = Clock::now();
      const auto problem = verify_solutions(SolutionReader::open(path), instance);
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      std::printf("%-10zu %2zu %12.3f\n", n, d, seconds);
      if (problem) {
        std::fprintf(stderr, "%s: %s\n", path.c_str(), problem->c_str());
        status = 1;
      }
    }
  return status;
}
