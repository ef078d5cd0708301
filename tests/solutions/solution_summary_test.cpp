#include "mosb/solution_summary.hpp"

#include <doctest/doctest.h>

#include <vector>

#include "golden_input.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "temp_dir.hpp"

using namespace mosb;

TEST_CASE("summarize: statuses, front sizes (lower median) and statistics over the queries") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "g.mosb");
  const auto instance = GraphReader::open(dir / "g.mosb", VerifyLevel::full);
  SolutionWriter w(instance, "Small_2");  // the `default` set: 3 queries
  QueryStatistics slow, fast;
  slow.runtime_seconds = 2.5;
  slow.expanded = 40;
  fast.runtime_seconds = 0.5;
  w.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25, 80, 3.75}, slow);
  w.set_query(1, QueryStatus::solved, std::vector<double>{120, 7.5}, fast);
  w.set_query(2, QueryStatus::timeout, std::vector<double>{});
  w.write(dir / "s.sol.mosb");
  const auto summary = summarize(SolutionReader::open_verified(dir / "s.sol.mosb"));
  CHECK(summary.status_counts[static_cast<std::size_t>(QueryStatus::solved)] == 2);
  CHECK(summary.status_counts[static_cast<std::size_t>(QueryStatus::timeout)] == 1);
  CHECK(summary.status_counts[static_cast<std::size_t>(QueryStatus::not_run)] == 0);
  REQUIRE(summary.front_sizes);
  CHECK(summary.front_sizes->min == 1);
  CHECK(summary.front_sizes->median == 1);  // of {1, 2}: the lower middle one
  CHECK(summary.front_sizes->max == 2);
  REQUIRE(summary.statistics.size() == 2);
  CHECK(summary.statistics[0].statistic == Statistic::runtime_seconds);
  CHECK(summary.statistics[0].queries == 2);
  CHECK(summary.statistics[0].total == 3.0);
  CHECK(summary.statistics[0].max == 2.5);
  CHECK(summary.statistics[1].statistic == Statistic::expanded);
  CHECK(summary.statistics[1].queries == 1);
  CHECK(summary.statistics[1].total == 40);

  SolutionWriter none(instance, "Small_2");
  none.write(dir / "none.sol.mosb");
  const auto empty = summarize(SolutionReader::open_verified(dir / "none.sol.mosb"));
  CHECK_FALSE(empty.front_sizes);
  CHECK(empty.status_counts[static_cast<std::size_t>(QueryStatus::not_run)] == 3);
  CHECK(empty.statistics.empty());
}
