#include "mosb/solution_summary.hpp"

#include <doctest/doctest.h>

#include <optional>
#include <string>
#include <vector>

#include "golden_input.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "temp_dir.hpp"

using namespace mosb;

TEST_CASE(
    "summarize: statuses and statistics. Front sizes and runtimes over the completed queries "
    "(the median of an even count is the middle pair's mean)") {
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
  const auto& statuses = summary.completed.statuses;
  CHECK(statuses[QueryStatus::solved] == 2);
  CHECK(statuses[QueryStatus::timeout] == 1);
  CHECK(statuses[QueryStatus::not_run] == 0);
  CHECK(statuses.total() == 3);
  CHECK(statuses.completed() == 2);
  REQUIRE(summary.completed.front_size);
  CHECK(summary.completed.front_size->count == 2);
  CHECK(summary.completed.front_size->min == 1);
  CHECK(summary.completed.front_size->median == 1.5);  // of {1, 2}: the middle pair's mean
  CHECK(summary.completed.front_size->max == 2);
  REQUIRE(summary.completed.runtime);
  CHECK(summary.completed.runtime->median == 1.5);
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
  CHECK_FALSE(empty.completed.front_size);
  CHECK(empty.completed.statuses[QueryStatus::not_run] == 3);
  CHECK(empty.statistics.empty());
}

TEST_CASE("summarize_completed: files pooled. A disconnected query completed with front size 0") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "g.mosb");
  const auto instance = GraphReader::open(dir / "g.mosb", VerifyLevel::full);
  SolutionWriter a(instance, "Small_2");
  QueryStatistics quick;
  quick.runtime_seconds = 1;
  a.set_query(0, QueryStatus::disconnected, std::vector<double>{}, quick);
  a.set_query(1, QueryStatus::solved, std::vector<double>{120, 7.5, 130, 6}, quick);
  a.set_query(2, QueryStatus::memory_limit, std::vector<double>{});
  a.write(dir / "a.sol");
  SolutionWriter b(instance, "Small_2");
  b.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25, 80, 3.75, 90, 2}, quick);
  b.write(dir / "b.sol");
  const auto ra = SolutionReader::open_verified(dir / "a.sol");
  const auto rb = SolutionReader::open_verified(dir / "b.sol");
  const SolutionReader* const both[] = {&ra, &rb};
  const auto pooled = summarize_completed(both);
  CHECK(pooled.statuses.total() == 6);
  CHECK(pooled.statuses[QueryStatus::not_run] == 2);
  CHECK(pooled.statuses[QueryStatus::memory_limit] == 1);
  REQUIRE(pooled.front_size);
  CHECK(pooled.front_size->count == 3);  // sizes 0, 2, 3
  CHECK(pooled.front_size->min == 0);
  CHECK(pooled.front_size->median == 2);
  CHECK(pooled.front_size->mean == doctest::Approx(5.0 / 3));
  CHECK(pooled.front_size->max == 3);
  CHECK(pooled.runtime->count == 3);
}

TEST_CASE("solver_name: the recorded name, else the file name without directory and extension") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "g.mosb");
  const auto instance = GraphReader::open(dir / "g.mosb", VerifyLevel::full);
  SolutionWriter unnamed(instance, "Small_2");
  unnamed.write(dir / "boa.sol");
  CHECK(solver_name(SolutionReader::open_verified(dir / "boa.sol")) == "boa");
  SolutionWriter named(instance, "Small_2");
  SolverInfo info;
  info.name = "BOA*";
  named.set_solver(info);
  named.write(dir / "named.sol");
  CHECK(solver_name(SolutionReader::open_verified(dir / "named.sol")) == "BOA*");
}

TEST_CASE(
    "choose_runtime and runtime_caption: the solvers' own runtimes only where every file has one "
    "of one clock, and a mix of clocks named") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "g.mosb");
  const auto instance = GraphReader::open(dir / "g.mosb", VerifyLevel::full);
  const auto file = [&](const std::string& name, std::optional<double> reported,
                        const std::string& clock) {
    SolutionWriter w(instance, "Small_2");
    SolverInfo info;
    info.name = name;
    if (!clock.empty()) info.parameters["profile.runtime_clock"] = clock;
    w.set_solver(info);
    QueryStatistics s;
    s.runtime_seconds = 1.0;
    s.reported_runtime_seconds = reported;
    w.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25}, s);
    w.write(dir / (name + ".sol"));
    return SolutionReader::open_verified(dir / (name + ".sol"));
  };
  const auto namoa = file("namoa", 0.5, ""), apex = file("apex", 0.25, "wall"),
             emoa = file("emoa", 0.75, "cpu"), plain = file("plain", std::nullopt, "");
  using Files = std::vector<const SolutionReader*>;
  CHECK(choose_runtime(Files{&namoa, &apex}) == RuntimeSource::reported);
  CHECK(runtime_caption(RuntimeSource::reported, Files{&namoa, &apex}) ==
        "runtime as each solver reported it");
  CHECK(choose_runtime(Files{&emoa}) == RuntimeSource::reported);
  CHECK(runtime_caption(RuntimeSource::reported, Files{&emoa}) ==
        "runtime as each solver reported it (cpu time)");
  // CPU time beside wall time: not compared unless asked, and then said.
  CHECK(choose_runtime(Files{&namoa, &emoa}) == RuntimeSource::wall);
  CHECK(runtime_caption(RuntimeSource::wall, Files{&namoa, &emoa}) ==
        "wall-clock runtime (mosb's measurement)");
  CHECK(choose_runtime(Files{&namoa, &emoa}, RuntimeSource::reported) == RuntimeSource::reported);
  CHECK(runtime_caption(RuntimeSource::reported, Files{&namoa, &emoa, &apex}) ==
        "runtime as each solver reported it (clocks differ: emoa cpu; the others wall)");
  // A file without the solver's own runtime makes the wall clock the only common one.
  CHECK(choose_runtime(Files{&namoa, &plain}) == RuntimeSource::wall);
  CHECK(choose_runtime(Files{}) == RuntimeSource::wall);
}
