// Solution files (spec/SOLUTIONS.md): the writer's checks, the reader's view of what was written,
// the binding to the instance, and the golden files in spec/golden/1.1/solutions.
#include "mosb/solution_file.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "file_patch.hpp"
#include "golden_input.hpp"
#include "golden_solutions.hpp"
#include "mosb/graph_builder.hpp"
#include "solution_faults.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;

namespace {
const std::filesystem::path kGolden = std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "golden";
const auto kSmall = kGolden / "1.0" / "valid" / "small.mosb";
const auto kSolutions = kGolden / "1.1" / "solutions";
}  // namespace

TEST_CASE("the solution writer reproduces the golden solution file byte for byte") {
  testing::TempDir dir;
  testing::write_golden_solutions(GraphReader::open(kSmall), dir / "small.sol.mosb");
  const auto written = testing::read_bytes(dir / "small.sol.mosb");
  const auto golden = testing::read_bytes(kSolutions / "valid" / "small.sol.mosb");
  REQUIRE_MESSAGE(!golden.empty(), "spec/golden/1.1/solutions/valid/small.sol.mosb is missing");
  CHECK_MESSAGE(written == golden,
                "the solution writer's output changed: if deliberate, update spec/SOLUTIONS.md "
                "and regenerate with mosb_make_golden solutions");
}

TEST_CASE("the golden solution file reads back with every value intact") {
  const auto instance = GraphReader::open(kSmall);
  const auto r = SolutionReader::open(kSolutions / "valid" / "small.sol.mosb", instance);
  CHECK_FALSE(r.verify_payload().has_value());
  CHECK(r.header().file_kind == 2);
  CHECK(r.header().version_minor == 1);
  CHECK(r.header().vertex_count == 4);
  CHECK(r.instance_digest() == instance.digest());
  CHECK(r.view_name() == "Small_2");
  CHECK(r.query_set() == "default");
  REQUIRE(r.objective_count() == 2);
  CHECK(r.objective_name(0) == "distance");
  CHECK(r.objective_type(0) == format::ElementType::u16);
  CHECK(r.objective_name(1) == "time");
  CHECK(r.objective_type(1) == format::ElementType::f32);
  REQUIRE(r.query_count() == 3);
  CHECK(r.vector_count() == 3);
  CHECK(r.status(0) == QueryStatus::solved);
  CHECK(r.status(2) == QueryStatus::timeout);
  CHECK(r.front_size(0) == 2);
  CHECK(r.front_size(2) == 0);
  const auto distance = r.front<std::uint16_t>(0, 0);
  CHECK(std::vector<std::uint16_t>(distance.begin(), distance.end()) ==
        std::vector<std::uint16_t>{60, 80});
  CHECK(r.front<float>(1, 1)[0] == 7.5f);
  CHECK(r.value_as_double(1, 1) == 3.75);
  CHECK_THROWS_AS(r.column<std::uint32_t>(0), Error);
  const auto sum = r.visit_column(0, [](auto column) {
    double total = 0;
    for (auto v : column) total += static_cast<double>(v);
    return total;
  });
  CHECK(sum == 260);
  CHECK(r.runtime_seconds(0) == 0.5);
  CHECK_FALSE(r.runtime_seconds(2).has_value());
  CHECK(r.count_statistic(Statistic::expanded, 1) == 5u);
  CHECK_FALSE(r.count_statistic(Statistic::peak_memory_bytes, 1).has_value());
  REQUIRE(r.has_paths());
  const auto path = r.path(1);
  CHECK(std::vector<std::uint32_t>(path.begin(), path.end()) ==
        std::vector<std::uint32_t>{0, 1, 2, 3});
  const auto solver = r.solver();
  CHECK(solver.name == "hand");
  CHECK(solver.epsilon == "0");
  CHECK(solver.parameters.at("order") == "lexicographic");
}

TEST_CASE("a solution file opened against another instance names both digests") {
  testing::TempDir dir;
  auto input = testing::golden_input();
  input.costs[0].values = std::vector<std::uint64_t>{41, 10, 30, 20, 50, 5, 300};
  write_graph(input, dir / "other.mosb");
  const auto other = GraphReader::open(dir / "other.mosb");
  const auto small = GraphReader::open(kSmall);
  try {
    (void)SolutionReader::open(kSolutions / "valid" / "small.sol.mosb", other);
    FAIL("opened against the wrong instance");
  } catch (const Error& e) {
    const std::string message = e.what();
    CHECK(e.code() == ErrorCode::invalid_argument);
    CHECK(message.find(small.digest()) != std::string::npos);
    CHECK(message.find(other.digest()) != std::string::npos);
  }
}

TEST_CASE("an instance is not a solution file and a solution file is not an instance") {
  CHECK_THROWS_WITH_AS(SolutionReader::open(kSmall), doctest::Contains("file kind 1"), Error);
  CHECK_THROWS_WITH_AS(GraphReader::open(kSolutions / "valid" / "small.sol.mosb"),
                       doctest::Contains("file kind 2"), Error);
}

TEST_CASE("the solution writer refuses what the instance's cost types cannot hold") {
  const auto instance = GraphReader::open(kSmall);
  SolutionWriter w(instance, "Small_2");
  CHECK(w.query_count() == 3);
  CHECK_THROWS_WITH(w.set_query(0, QueryStatus::solved, std::vector<double>{60.5, 1}),
                    doctest::Contains("does not fit the objective's type u16"));
  CHECK_THROWS_WITH(w.set_query(0, QueryStatus::solved, std::vector<double>{70000, 1}),
                    doctest::Contains("u16"));
  CHECK_THROWS_WITH(w.set_query(0, QueryStatus::solved, std::vector<double>{1, 0.1}),
                    doctest::Contains("f32"));
  CHECK_THROWS_WITH(w.set_query(0, QueryStatus::solved, std::vector<double>{1, -1}),
                    doctest::Contains("negative"));
  CHECK_THROWS_WITH(w.set_query(0, QueryStatus::solved, std::vector<double>{1, 2, 3}),
                    doctest::Contains("not a whole number"));
  CHECK_THROWS_WITH(w.set_query(3, QueryStatus::solved, std::vector<double>{1, 2}),
                    doctest::Contains("is not in query set 'default'"));
  CHECK_THROWS_WITH(w.set_query(1, QueryStatus::timeout, std::vector<double>{1, 2}),
                    doctest::Contains("only solved queries"));
  CHECK_THROWS_WITH(w.set_query(1, QueryStatus::timeout, {}, {1.0, {}, {}, {}}),
                    doctest::Contains("carries no statistics"));
  CHECK_THROWS_WITH(w.set_query(1, QueryStatus::solved, {}), doctest::Contains("empty front"));
}

TEST_CASE("queries never set are written as not-run, and the file binds to the view") {
  testing::TempDir dir;
  const auto instance = GraphReader::open(kSmall);
  SolutionWriter w(instance, "Small_2");
  w.set_query(1, QueryStatus::disconnected, {}, {2.0, 10, 12, 4096});
  w.write(dir / "s.sol.mosb");
  const auto r = SolutionReader::open(dir / "s.sol.mosb", instance);
  CHECK_FALSE(r.verify_payload().has_value());
  CHECK(r.status(0) == QueryStatus::not_run);
  CHECK(r.status(1) == QueryStatus::disconnected);
  CHECK(r.vector_count() == 0);
  CHECK_FALSE(r.has_paths());
  CHECK(r.statistics(1).peak_memory_bytes == 4096u);
  CHECK(parse_query_status("memory-limit") == QueryStatus::memory_limit);
  CHECK(to_string(QueryStatus::not_run) == "not-run");
}

TEST_CASE("every golden invalid solution file fails where EXPECTED.tsv says") {
  int cases = 0;
  for (const auto& row : testing::expected_rows(kSolutions / "invalid" / "EXPECTED.tsv")) {
    REQUIRE(row.size() == 3);
    const auto &file = row[0], &stage = row[1], &expected = row[2];
    CAPTURE(file);
    ++cases;
    const auto path = kSolutions / "invalid" / file;
    if (stage == "open") {
      CHECK_THROWS_WITH_AS(SolutionReader::open(path), doctest::Contains(expected.c_str()), Error);
      continue;
    }
    const auto r = SolutionReader::open(path);
    const auto problem = r.verify_payload();
    REQUIRE(problem.has_value());
    CHECK_MESSAGE(problem->find(expected) != std::string::npos, *problem);
  }
  CHECK(cases == static_cast<int>(std::size(testing::kSolutionFaults)));
}
