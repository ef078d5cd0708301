// Section kind 17 (query_reference, spec/SOLUTIONS.md §6): written with a query set, checked at
// open and by verify, read back by GraphReader::query_reference; Moving AI's published optima
// against the true length optimum of our octile graph.
#include <doctest/doctest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <queue>

#include "golden_input.hpp"
#include "mosb/converters/movingai.hpp"
#include "mosb/error.hpp"
#include "mosb/instance_editor.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_verify.hpp"
#include "mosb/verify.hpp"
#include "requirements.hpp"
#include "temp_dir.hpp"

using namespace mosb;
using namespace mosb::converters;

namespace {

GraphInput with_reference(std::vector<double> values, std::string objective = "distance") {
  auto g = testing::golden_input();
  g.queries[0].reference = QueryReference{std::move(objective), "test", std::move(values)};
  return g;
}

std::string write_error(const GraphInput& g, const std::filesystem::path& path) {
  try {
    write_graph(g, path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// The smallest sum of `cost` from start to goal (Dijkstra over the forward CSR); UINT64_MAX when
// the goal is unreachable.
std::uint64_t shortest(const GraphReader& r, const std::vector<std::uint64_t>& cost,
                       std::uint32_t start, std::uint32_t goal) {
  const auto offsets = r.forward_offsets();
  const auto targets = r.forward_targets();
  std::vector<std::uint64_t> dist(r.vertex_count(), UINT64_MAX);
  using Item = std::pair<std::uint64_t, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[start] = 0;
  open.push({0, start});
  while (!open.empty()) {
    const auto [d, v] = open.top();
    open.pop();
    if (v == goal) return d;
    if (d > dist[v]) continue;
    for (auto a = offsets[v]; a < offsets[v + 1]; ++a)
      if (d + cost[a] < dist[targets[a]]) {
        dist[targets[a]] = d + cost[a];
        open.push({dist[targets[a]], targets[a]});
      }
  }
  return UINT64_MAX;
}

// §6's bracket for Moving AI's optima of the games `length`.
std::optional<std::string> movingai_bracket(double c_star, double l_star) {
  return reference_problem(c_star, l_star, {"length", "movingai-optimal", ReferenceUnits::octile});
}

}  // namespace

TEST_CASE("query_reference: written after its set, read back, absent on other sets") {
  testing::TempDir dir;
  write_graph(with_reference({1.5, 0, 2.25}), dir / "r.mosb");
  const auto r = GraphReader::open(dir / "r.mosb", VerifyLevel::full);
  const auto ref = r.query_reference("default");
  REQUIRE(ref.has_value());
  CHECK(std::vector<double>(ref->begin(), ref->end()) == std::vector<double>{1.5, 0, 2.25});
  CHECK_FALSE(r.query_reference("reverse").has_value());
  CHECK_THROWS_WITH_AS(r.query_reference("nosuch"), doctest::Contains("no query set named"), Error);
  CHECK(r.metadata().get("queries.default.reference.objective") == "distance");
  CHECK(r.metadata().get("queries.default.reference.source") == "test");
  CHECK(r.header().version_minor == 0);  // kind 17 is ignorable by a 1.0 reader: the file stays 1.0
  // Without the reference the same input writes the golden file's bytes (nothing else moved).
  write_graph(testing::golden_input(), dir / "plain.mosb");
  CHECK(GraphReader::open(dir / "plain.mosb").sections().size() + 1 == r.sections().size());
}

TEST_CASE("query_reference: the writer refuses a wrong count, a bad value, an unknown objective") {
  testing::TempDir dir;
  CHECK(write_error(with_reference({1, 2}), dir / "a.mosb") ==
        "query set 'default': reference has 2 values for 3 queries");
  CHECK(write_error(with_reference({1, -2, 3}), dir / "a.mosb") ==
        "query set 'default': reference, query 1: -2.000000 is not a finite number >= 0");
  CHECK(write_error(with_reference({1, NAN, 3}), dir / "a.mosb").find("query 1") !=
        std::string::npos);
  CHECK(write_error(with_reference({1, 2, 3}, "nosuch"), dir / "a.mosb") ==
        "query set 'default': reference names objective 'nosuch', which is no cost section");
  CHECK_FALSE(std::filesystem::exists(dir / "a.mosb"));
}

TEST_CASE("query_reference: rewrite_instance keeps, drops and replaces references") {
  testing::TempDir dir;
  write_graph(with_reference({1, 2, 3}), dir / "r.mosb");
  const auto source = GraphReader::open(dir / "r.mosb", VerifyLevel::full);
  // Another set replaced: the reference of `default` is copied unchanged.
  rewrite_instance(source, source.metadata(), {{"reverse", {{1, 2}}}}, dir / "keep.mosb");
  const auto keep = GraphReader::open(dir / "keep.mosb", VerifyLevel::full);
  CHECK(keep.query_reference("default")->size() == 3);
  // `default` replaced by a set without a reference: the old section goes with it.
  Metadata m;
  for (const auto& [key, value] : source.metadata().entries())
    if (!key.starts_with("queries.default.reference.")) m.set(key, value);
  rewrite_instance(source, m, {{"default", {{0, 1}}}}, dir / "drop.mosb");
  const auto drop = GraphReader::open(dir / "drop.mosb", VerifyLevel::full);
  CHECK_FALSE(drop.query_reference("default").has_value());
  CHECK_FALSE(verify(drop, VerifyLevel::full).has_value());
  // Replaced by a set with a reference of another length.
  rewrite_instance(source, m,
                   {{"default", {{0, 1}, {2, 3}}, QueryReference{"time", "again", {4, 5}}}},
                   dir / "new.mosb");
  const auto fresh = GraphReader::open(dir / "new.mosb", VerifyLevel::full);
  CHECK((*fresh.query_reference("default"))[1] == 5);
  CHECK(fresh.metadata().get("queries.default.reference.objective") == "time");
}

TEST_CASE("query_reference: verify checks values and the objective named in the metadata") {
  testing::TempDir dir;
  write_graph(with_reference({1, 2, 3}), dir / "r.mosb");
  const auto r = GraphReader::open(dir / "r.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  // The metadata rewritten to name a missing objective.
  Metadata m = r.metadata();
  m.set("queries.default.reference.objective", "nosuch");
  rewrite_instance(r, m, {}, dir / "bad.mosb");
  const auto bad = GraphReader::open(dir / "bad.mosb");
  const auto problem = verify(bad, VerifyLevel::structure);
  REQUIRE(problem.has_value());
  CHECK(problem->find("[metadata-reference] queries.default.reference.objective names objective "
                      "'nosuch', which is no cost section") != std::string::npos);
}

TEST_CASE("movingai: scenario optimal must be a finite non-negative decimal, located") {
  const std::string row = "0\tm.map\t3\t3\t0\t0\t2\t2\t";
  for (const char* bad : {"-1", "1e999", "nan", "inf", "x", ".5", "1,5"}) {
    CAPTURE(bad);
    CHECK_THROWS_WITH_AS(parse_scenario("version 1\n" + row + bad + "\n", "s.scen"),
                         doctest::Contains("s.scen:2:21: expected the optimal length"), Error);
  }
  CHECK(parse_scenario("version 1\n" + row + "2.82842712\n", "s.scen")[0].optimal == 2.82842712);
}

TEST_CASE("movingai bracket: §6's inequalities, both sides") {
  CHECK_FALSE(movingai_bracket(28, 2.82842712).has_value());  // one diagonal pair: 2·14
  CHECK_FALSE(movingai_bracket(20, 2).has_value());
  CHECK(movingai_bracket(30, 2.82842712)->find("c*/10 = 3 > L* + tau") != std::string::npos);
  CHECK(movingai_bracket(20, 2.82842712)->find("L* > (sqrt 2/1.4) c*/10 + tau") !=
        std::string::npos);
  CHECK_FALSE(movingai_bracket(10, 1.000001).has_value());  // within tau
}

TEST_CASE("movingai: published optima bracket the true length optimum (shared/data/movingai)") {
  const auto data = testing::shared_data() / "movingai";
  testing::require_shared(data / "arena2.map");
  testing::TempDir dir;
  for (const char* name : {"arena2.map", "random512-20-1.map"}) {
    CAPTURE(name);
    MovingaiOptions o;
    o.map_file = (data / name).string();
    o.scen_file = (data / (std::string(name) + ".scen")).string();
    write_graph(convert_movingai(o), dir / "m.mosb");
    const auto r = GraphReader::open(dir / "m.mosb", VerifyLevel::full);
    const auto queries = r.queries("scen");
    const auto ref = r.query_reference("scen");
    REQUIRE(ref.has_value());
    REQUIRE(ref->size() == queries.size());
    std::vector<std::uint64_t> length(r.arc_count());
    r.read_cost_as(r.objective_index("length"), std::span(length));
    // 50 queries spread over the file (scenarios are sorted by bucket, i.e. by length).
    const std::size_t sample = 50;
    for (std::size_t k = 0; k < sample; ++k) {
      const std::size_t q = k * queries.size() / sample;
      CAPTURE(q);
      const auto c_star = shortest(r, length, queries[q].start, queries[q].goal);
      REQUIRE(c_star != UINT64_MAX);
      const auto problem = movingai_bracket(static_cast<double>(c_star), (*ref)[q]);
      CHECK_MESSAGE(!problem.has_value(), *problem);
    }
    // The tight row that sized tau (SOLUTIONS.md §6): an all-diagonal optimal path, where the
    // upper bound is exact, with 2 sqrt 2 = 2.8284271 printed as 2.82843 (6 significant digits).
    // It passes; a value one unit off in that last printed digit does not.
    if (std::string(name) == "arena2.map") {
      CHECK(shortest(r, length, queries[1].start, queries[1].goal) == 28);
      CHECK((*ref)[1] == 2.82843);
      CHECK_FALSE(movingai_bracket(28, (*ref)[1]).has_value());
      CHECK_FALSE(movingai_bracket(28, 2 * std::sqrt(2.0)).has_value());
      CHECK(movingai_bracket(28, 2.82853).has_value());
    }
  }
}

TEST_CASE("solutions verify: a declared reference of any source is checked in its declared units") {
  // Small_2 (distance, time) on `default`: query 0's front is (60, 5.25) and (80, 3.75), query 1's
  // (120, 7.5).
  testing::TempDir dir;
  auto verify_front = [&](std::vector<double> optima, const char* units,
                          std::vector<double> query_1) {
    auto g = testing::golden_input();
    g.queries[0].reference = QueryReference{"distance", "published-optimum", std::move(optima)};
    if (units) g.metadata.set("queries.default.reference.units", units);
    write_graph(g, dir / "r.mosb");
    const auto instance = GraphReader::open(dir / "r.mosb", VerifyLevel::full);
    SolutionWriter w(instance, "Small_2");
    w.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25, 80, 3.75});
    w.set_query(1, QueryStatus::solved, query_1);
    w.write(dir / "s.sol.mosb");
    return verify_solutions(SolutionReader::open(dir / "s.sol.mosb", instance), instance);
  };
  // No units: octile, Moving AI's. The optima 6 and 12 bracket the smallest distances 60 and 120.
  CHECK_FALSE(verify_front({6, 12, 0}, nullptr, {120, 7.5}).has_value());
  auto problem = verify_front({6, 12, 0}, nullptr, {130, 7.5});
  REQUIRE(problem.has_value());
  CHECK(*problem ==
        "query 1: [reference] the smallest distance c* = 130 does not match the published-optimum "
        "optimum L* = 12: c*/10 = 13 > L* + tau (spec/SOLUTIONS.md section 6)");
  CHECK(*problem ==
        "query 1: " +
            *reference_problem(130, 12, {"distance", "published-optimum", ReferenceUnits::octile}));
  CHECK_FALSE(verify_front({6, 12, 0}, "octile", {120, 7.5}).has_value());
  // Units of the objective itself: the smallest distance must be the optimum.
  CHECK_FALSE(verify_front({60, 120, 0}, "objective", {120, 7.5}).has_value());
  problem = verify_front({60, 120, 0}, "objective", {130, 7.5});
  REQUIRE(problem.has_value());
  CHECK(*problem ==
        "query 1: [reference] the smallest distance c* = 130 does not match the published-optimum "
        "optimum L* = 120: |c* - L*| > tau (spec/SOLUTIONS.md section 6)");
  // The octile optima read as the objective's own units fail, and the reverse.
  CHECK(verify_front({6, 12, 0}, "objective", {120, 7.5}).has_value());
  CHECK(verify_front({60, 120, 0}, nullptr, {120, 7.5}).has_value());
  // Other units are refused by verify (rule metadata-reference).
  auto g = testing::golden_input();
  g.queries[0].reference = QueryReference{"distance", "published-optimum", {6, 12, 0}};
  g.metadata.set("queries.default.reference.units", "miles");
  write_graph(g, dir / "bad.mosb");
  const auto bad = verify(GraphReader::open(dir / "bad.mosb"), VerifyLevel::structure);
  REQUIRE(bad.has_value());
  CHECK(bad->find("[metadata-reference] queries.default.reference.units is 'miles', not octile "
                  "or objective") != std::string::npos);
}
