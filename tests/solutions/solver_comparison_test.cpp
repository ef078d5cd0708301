#include "mosb/solver_comparison.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "golden_input.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

struct Outcome {
  QueryStatus status;
  std::vector<double> costs;
  std::optional<double> runtime;
  std::optional<double> reported = std::nullopt;  // reported_runtime_seconds
};

// The golden instance (views Small_2, Small_5), written into `dir`.
GraphReader golden_instance(const testing::TempDir& dir) {
  write_graph(testing::golden_input(), dir / "g.mosb");
  return GraphReader::open(dir / "g.mosb", VerifyLevel::full);
}

// A solution file of the golden instance's view Small_2 (3 queries, objectives c1 u32 and c2 f32).
SolutionReader write_solutions(const testing::TempDir& dir, const GraphReader& instance,
                               const std::string& name, const std::vector<Outcome>& queries,
                               const std::string& epsilon = "0") {
  SolutionWriter w(instance, "Small_2");
  w.set_solver({name, "1", {}, epsilon, ""});
  for (std::size_t q = 0; q < queries.size(); ++q) {
    QueryStatistics statistics;
    statistics.runtime_seconds = queries[q].runtime;
    statistics.reported_runtime_seconds = queries[q].reported;
    w.set_query(q, queries[q].status, queries[q].costs, statistics);
  }
  w.write(dir / (name + ".sol"));
  return SolutionReader::open_verified(dir / (name + ".sol"));
}

}  // namespace

TEST_CASE("distribution_of: median of odd and even counts, mean, max, shifted geometric mean") {
  CHECK_FALSE(distribution_of({}));
  const auto odd = distribution_of({3, 1, 2});
  REQUIRE(odd);
  CHECK(odd->count == 3);
  CHECK(odd->median == 2);
  CHECK(odd->mean == 2);
  CHECK(odd->max == 3);
  const auto even = distribution_of({4, 1, 2, 10}, 1.0);
  REQUIRE(even);
  CHECK(even->median == 3);  // (2 + 4) / 2
  CHECK(even->mean == doctest::Approx(4.25));
  // exp(mean(ln(x + 1))) − 1 = (5·2·3·11)^(1/4) − 1
  CHECK(even->shifted_geometric_mean == doctest::Approx(std::pow(330.0, 0.25) - 1));
  const auto with_infinity = distribution_of({0, std::numeric_limits<double>::infinity()});
  REQUIRE(with_infinity);
  CHECK(std::isinf(with_infinity->max));
}

TEST_CASE("compare_solvers: per-solver statuses, coverage, ratios and runtimes on common queries") {
  testing::TempDir dir;
  const auto instance = golden_instance(dir);
  const auto reference = write_solutions(dir, instance, "ref",
                                         {{QueryStatus::solved, {10, 40, 20, 20, 40, 10}, 9.0},
                                          {QueryStatus::solved, {30, 30}, 9.0},
                                          {QueryStatus::disconnected, {}, 1.0}});
  std::vector<SolutionReader> solvers;
  // Exact on query 0, 10 % off on query 1 (as its ε allows), disconnected agreed.
  solvers.push_back(write_solutions(dir, instance, "fast",
                                    {{QueryStatus::solved, {10, 40, 20, 20, 40, 10}, 1.0},
                                     {QueryStatus::solved, {33, 30}, 3.0},
                                     {QueryStatus::disconnected, {}, 0.5}},
                                    "0.1"));
  // Half of query 0's front, a timeout on query 1.
  solvers.push_back(write_solutions(dir, instance, "slow",
                                    {{QueryStatus::solved, {20, 20}, 4.0},
                                     {QueryStatus::timeout, {}, std::nullopt},
                                     {QueryStatus::disconnected, {}, 2.0}}));
  const std::vector<Ratio> eps{parse_epsilon("0"), parse_epsilon("0.1")};
  const auto result = compare_solvers(reference, solvers, eps);
  REQUIRE(result.solvers.size() == 2);
  // Both completed queries 0 and 2: the runtime sample of both solvers.
  CHECK(result.common_queries == std::vector<std::uint64_t>{0, 2});
  CHECK(result.failed);

  const auto& fast = result.solvers[0];
  CHECK(fast.name == "fast");
  CHECK(fast.own.statuses[QueryStatus::solved] == 2);
  CHECK(fast.not_solved == 0);
  CHECK(fast.per_epsilon[0].covered == 1);  // ε = 0: query 0 only
  CHECK(fast.per_epsilon[0].not_covered == 1);
  CHECK(fast.per_epsilon[1].covered == 2);
  REQUIRE(fast.achieved_epsilon);
  CHECK(fast.achieved_epsilon->max == doctest::Approx(0.1));
  CHECK(fast.achieved_epsilon->median == doctest::Approx(0.05));
  REQUIRE(fast.runtime);
  CHECK(fast.runtime->count == 2);  // queries 0 and 2; query 1 is not common
  CHECK(fast.runtime->median == 0.75);
  CHECK(fast.runtime->max == 1.0);

  const auto& slow = result.solvers[1];
  CHECK(slow.own.statuses[QueryStatus::timeout] == 1);
  CHECK(slow.not_solved == 1);
  CHECK(slow.per_epsilon[1].covered == 0);
  CHECK(slow.per_epsilon[1].not_covered == 1);
  REQUIRE(slow.size_ratio);
  CHECK(slow.size_ratio->median == doctest::Approx(1.0 / 3));
  CHECK(slow.achieved_epsilon->max == 1);  // (20, 20) covers (10, 40) and (40, 10) at ε = 1
  REQUIRE(slow.runtime);
  CHECK(slow.runtime->mean == 3.0);
}

TEST_CASE("compare_solvers: two files of one solver are told apart by their files") {
  testing::TempDir dir;
  const auto instance = golden_instance(dir);
  const std::vector<Outcome> queries{{QueryStatus::solved, {30, 30}, 1.0},
                                     {QueryStatus::solved, {30, 30}, 1.0},
                                     {QueryStatus::disconnected, {}, 1.0}};
  const auto reference = write_solutions(dir, instance, "ref", queries);
  std::vector<SolutionReader> runs;
  runs.push_back(SolutionReader::open_verified(dir / "ref.sol"));
  runs.push_back(SolutionReader::open_verified(dir / "ref.sol"));
  const std::vector<Ratio> eps{parse_epsilon("0")};
  const auto result = compare_solvers(reference, runs, eps);
  CHECK(result.solvers[0].name == "ref (" + (dir / "ref.sol").string() + ")");
  CHECK(result.solvers[1].name == result.solvers[0].name);  // the same file twice: no better
  CHECK_FALSE(result.failed);
  CHECK_THROWS_AS(compare_solvers(reference, std::span<const SolutionReader>{}, eps), Error);
}

TEST_CASE("compare_fronts: equal sets, the first difference and its side, status differences") {
  testing::TempDir dir;
  const auto instance = golden_instance(dir);
  const auto a = write_solutions(dir, instance, "a",
                                 {{QueryStatus::solved, {10, 40, 20, 20}, 1.0},
                                  {QueryStatus::solved, {30, 30}, 2.0},
                                  {QueryStatus::timeout, {}, std::nullopt}});
  const auto b = write_solutions(dir, instance, "b",
                                 {{QueryStatus::solved, {20, 20, 10, 40}, 3.0},
                                  {QueryStatus::solved, {30, 30, 25, 31}, 2.0},
                                  {QueryStatus::disconnected, {}, 1.0}});
  const auto r = compare_fronts(a, b);
  REQUIRE(r.queries.size() == 3);
  CHECK(r.queries[0].equal);  // the same set in another order
  CHECK(*r.queries[0].runtime_ratio == 3.0);
  CHECK_FALSE(r.queries[1].equal);
  CHECK(r.queries[1].first_difference == std::vector<double>{25, 31});
  CHECK_FALSE(r.queries[1].difference_in_a);
  CHECK_FALSE(r.queries[2].equal);
  CHECK(r.queries[2].first_difference.empty());
  CHECK_FALSE(r.queries[2].runtime_ratio);
  CHECK(r.equal == 1);
  CHECK(r.different == 2);
  REQUIRE(r.runtime_ratio);
  CHECK(r.runtime_ratio->count == 2);
}

TEST_CASE("float objectives are equal within the tolerance, integer objectives exactly") {
  // Issue 33 §3: two exact solvers' f64 sums differ in the last bits (EMOA* and NAMOA* on a
  // roadmap: 0 of 12 queries equal, the largest relative difference 6.2e-16). Small_2 is c1
  // (u32, sums u64: exact) and c2 (f32, sums f64: within the tolerance).
  testing::TempDir dir;
  const auto instance = golden_instance(dir);
  const double c2 = 43.88583999999999, c2_next = std::nextafter(c2, 100.0);
  const auto a = write_solutions(dir, instance, "a",
                                 {{QueryStatus::solved, {10, c2, 20, 7}, 1.0},
                                  {QueryStatus::solved, {1000000000, 5}, 1.0},
                                  {QueryStatus::solved, {30, 1}, 1.0}});
  const auto b = write_solutions(dir, instance, "b",
                                 {{QueryStatus::solved, {20, 7 * (1 + 4e-10), 10, c2_next}, 1.0},
                                  {QueryStatus::solved, {1000000001, 5}, 1.0},
                                  {QueryStatus::solved, {30, 1.000001}, 1.0}});
  const auto r = compare_fronts(a, b);
  CHECK(r.tolerance == kDefaultTolerance);
  CHECK(r.queries[0].equal);        // within 1e-9 in c2, equal in c1
  CHECK_FALSE(r.queries[1].equal);  // c1 is an integer objective: 1e-9 apart is different
  CHECK_FALSE(r.queries[2].equal);  // 1e-6 is beyond the tolerance
  CHECK(r.queries[2].first_difference == std::vector<double>{30, 1});  // stored values shown
  ComparisonOptions exact;
  exact.tolerance = 0;
  CHECK_FALSE(compare_fronts(a, b, exact).queries[0].equal);
  ComparisonOptions loose;
  loose.tolerance = 1e-5;
  CHECK(compare_fronts(a, b, loose).queries[2].equal);
  CHECK_FALSE(
      compare_fronts(a, b, loose).queries[1].equal);  // integers stay exact at any tolerance
  ComparisonOptions bad;
  bad.tolerance = 1;
  CHECK_THROWS_AS(compare_fronts(a, b, bad), Error);
  bad.tolerance = -1e-9;
  CHECK_THROWS_AS(compare_fronts(a, b, bad), Error);

  // eval: ε = 0 is the same multiset within the tolerance, and coverage uses it.
  const std::vector<SolutionReader> solvers{b};
  const std::vector<Ratio> eps{parse_epsilon("0"), parse_epsilon("0.01")};
  const auto result = compare_solvers(a, solvers, eps);
  const auto& q0 = result.solvers[0].evaluation.queries[0];
  REQUIRE(q0.front);
  CHECK(q0.front->same_multiset);
  CHECK(q0.front->achieved_value == 0);
  CHECK(q0.front->dominated_by_reference.empty());
  CHECK(q0.outcome(0) == QueryOutcome::covered);
  // Exactly: (20, 7.0000000028) is dominated by the reference's (20, 7), a "solver bug".
  const auto strict = compare_solvers(a, solvers, eps, exact);
  CHECK(strict.solvers[0].evaluation.queries[0].outcome(0) == QueryOutcome::dominated);
  CHECK(strict.solvers[0].evaluation.queries[0].front->achieved_value > 0);
}

TEST_CASE("eval counts why each query fails: not covered, dominated (an exact claim), not solved") {
  // Issue 33 §2: "ε=0: 2 covered, 1 not covered" hid that the failure was a dominated vector.
  testing::TempDir dir;
  const auto instance = golden_instance(dir);
  const auto reference = write_solutions(dir, instance, "ref",
                                         {{QueryStatus::solved, {10, 40, 20, 20}, 1.0},
                                          {QueryStatus::solved, {30, 30}, 1.0},
                                          {QueryStatus::solved, {5, 5}, 1.0}});
  // Query 0: the reference's front plus a vector it dominates; query 1: 10 % off in c1 (and not
  // dominated: better in c2); query 2: a timeout.
  const std::vector<Outcome> outcomes{{QueryStatus::solved, {10, 40, 20, 20, 25, 25}, 1.0},
                                      {QueryStatus::solved, {33, 28}, 1.0},
                                      {QueryStatus::timeout, {}, std::nullopt}};
  const std::vector<SolutionReader> exact{write_solutions(dir, instance, "exact", outcomes)};
  const std::vector<Ratio> eps{parse_epsilon("0"), parse_epsilon("0.2")};
  const auto result = compare_solvers(reference, exact, eps);
  const auto& s = result.solvers[0];
  const auto& q0 = s.evaluation.queries[0];
  CHECK(q0.dominated);
  CHECK(q0.front->coverage[0].uncovered == 0);
  CHECK(q0.front->coverage[0].extra == 1);
  CHECK(q0.outcome(0) == QueryOutcome::dominated);
  CHECK(q0.outcome(1) == QueryOutcome::dominated);  // fails at every ε
  CHECK(s.evaluation.queries[2].outcome(0) == QueryOutcome::not_solved);
  CHECK(s.not_solved == 1);
  CHECK(s.per_epsilon[0].covered == 0);
  CHECK(s.per_epsilon[0].not_covered == 1);  // query 1
  CHECK(s.per_epsilon[0].dominated == 1);    // query 0
  CHECK(s.per_epsilon[1].covered == 1);      // query 1 at 0.2
  CHECK(s.per_epsilon[1].not_covered == 0);
  CHECK(s.per_epsilon[1].dominated == 1);
  // The same fronts from a solver that declares ε = 0.1: a dominated vector is no bug.
  const std::vector<SolutionReader> approx{
      write_solutions(dir, instance, "approx", outcomes, "0.1")};
  const auto relaxed = compare_solvers(reference, approx, eps).solvers[0];
  CHECK(relaxed.per_epsilon[0].dominated == 0);
  CHECK(relaxed.per_epsilon[0].not_covered == 2);
  CHECK(relaxed.per_epsilon[1].covered == 2);
}

TEST_CASE("the runtime summarised: the wall clock, or the solver's reported figure") {
  testing::TempDir dir;
  const auto instance = golden_instance(dir);
  const auto reference = write_solutions(dir, instance, "ref",
                                         {{QueryStatus::solved, {30, 30}, 1.0},
                                          {QueryStatus::solved, {30, 30}, 1.0},
                                          {QueryStatus::solved, {30, 30}, 1.0}});
  const std::vector<SolutionReader> solvers{
      write_solutions(dir, instance, "reports",
                      {{QueryStatus::solved, {30, 30}, 2.0, 0.5},
                       {QueryStatus::solved, {30, 30}, 4.0, 1.5},
                       {QueryStatus::solved, {30, 30}, 6.0, 2.5}}),
      write_solutions(dir, instance, "silent",
                      {{QueryStatus::solved, {30, 30}, 1.0},
                       {QueryStatus::solved, {30, 30}, 1.0},
                       {QueryStatus::solved, {30, 30}, 1.0}})};
  const std::vector<Ratio> eps{parse_epsilon("0")};
  const auto wall = compare_solvers(reference, solvers, eps);
  CHECK(wall.runtime == RuntimeSource::wall);
  CHECK(wall.solvers[0].runtime->median == 4.0);
  CHECK(wall.solvers[1].runtime_recorded);
  ComparisonOptions options;
  options.runtime = RuntimeSource::reported;
  const auto reported = compare_solvers(reference, solvers, eps, options);
  CHECK(reported.runtime == RuntimeSource::reported);
  REQUIRE(reported.solvers[0].runtime);
  CHECK(reported.solvers[0].runtime->median == 1.5);
  CHECK(reported.solvers[0].runtime_recorded);
  CHECK_FALSE(reported.solvers[1].runtime);  // no reported runtimes: no sample, and it says so
  CHECK_FALSE(reported.solvers[1].runtime_recorded);
  const auto ratios = compare_fronts(solvers[1], solvers[0], options);
  CHECK_FALSE(ratios.runtime_ratio);  // the first file reports none
  const auto wall_ratios = compare_fronts(solvers[1], solvers[0]);
  REQUIRE(wall_ratios.runtime_ratio);
  CHECK(wall_ratios.runtime_ratio->median == 4.0);
  CHECK(kRuntimeSourceNames.parse("reported") == RuntimeSource::reported);
}
