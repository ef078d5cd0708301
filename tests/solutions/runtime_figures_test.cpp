#include "mosb/runtime_figures.hpp"

#include <doctest/doctest.h>

#include <stdexcept>
#include <vector>

using namespace mosb;

namespace {
constexpr auto kSolved = QueryStatus::solved;
constexpr auto kDisconnected = QueryStatus::disconnected;
constexpr auto kTimeout = QueryStatus::timeout;
}  // namespace

TEST_CASE("cactus_series: solved queries with a runtime, sorted, 0 s counted and not drawn") {
  const std::vector<QueryRun> runs = {{kSolved, 3.0},       {kTimeout, 9.0}, {kSolved, 0.0},
                                      {kDisconnected, 0.5}, {kSolved, 1.0},  {kSolved, {}}};
  const auto series = cactus_series(runs);
  CHECK(series.solved == 3);
  CHECK(series.zero == 1);
  // The k-th fastest at k, counting the one at 0 s.
  CHECK(series.points == std::vector<FigurePoint>{{2, 1.0}, {3, 3.0}});
  CHECK(cactus_series({}).points.empty());
}

TEST_CASE("performance_profile: steps over the queries some solver solved, ties once") {
  // Three queries; the third solved by nobody, so two are profiled.
  const std::vector<std::vector<QueryRun>> runs = {
      {{kSolved, 1.0}, {kSolved, 2.0}},
      {{kSolved, 4.0}, {kSolved, 2.0}},
      {{kTimeout, {}}, {kTimeout, {}}},
  };
  const auto profile = performance_profile(runs, 2);
  CHECK(profile.queries == 2);
  REQUIRE(profile.series.size() == 2);
  CHECK(profile.series[0] == std::vector<FigurePoint>{{1, 0.5}, {2, 1.0}});
  CHECK(profile.series[1] == std::vector<FigurePoint>{{1, 0.5}, {2, 1.0}});
  // A solver never the best starts at (1, 0); one that solves nothing has no step.
  const auto slow = performance_profile({{{kSolved, 1.0}, {kSolved, 3.0}, {kTimeout, {}}}}, 3);
  CHECK(slow.series[1] == std::vector<FigurePoint>{{1, 0}, {3, 1.0}});
  CHECK(slow.series[2].empty());
  // 0 s divides as 1e-6 s.
  const auto zero = performance_profile({{{kSolved, 0.0}, {kSolved, 1e-6}}}, 2);
  CHECK(zero.series[0] == std::vector<FigurePoint>{{1, 1.0}});
  CHECK(zero.series[1] == std::vector<FigurePoint>{{1, 1.0}});
  CHECK_THROWS_AS(performance_profile({{{kSolved, 1.0}}}, 2), std::invalid_argument);
}

TEST_CASE("runtime_scatter: queries both completed, the others counted") {
  const std::vector<QueryRun> a = {{kSolved, 1.0}, {kDisconnected, 2.0}, {kSolved, 1.0},
                                   {kTimeout, {}}, {kSolved, 0.0},       {kTimeout, {}}};
  const std::vector<QueryRun> b = {{kSolved, 3.0}, {kSolved, 0.5}, {kTimeout, {}},
                                   {kSolved, 1.0}, {kSolved, 2.0}, {kTimeout, {}}};
  const auto scatter = runtime_scatter(a, b);
  CHECK(scatter.points == std::vector<FigurePoint>{{1.0, 3.0}, {2.0, 0.5}});
  CHECK(scatter.query == std::vector<std::size_t>{0, 1});
  CHECK(scatter.one_only == 2);
  CHECK(scatter.zero == 1);
  CHECK_THROWS_AS(runtime_scatter(a, std::span(b).first(2)), std::invalid_argument);
}
