#include "mosb/stats.hpp"

#include <doctest/doctest.h>

#include <cmath>

#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

CostColumn integer_column(std::string name, std::vector<std::uint64_t> values) {
  return {std::move(name), "", std::move(values), std::nullopt};
}

// A graph whose arcs are (tails[i], heads[i]) with the given cost columns, written and reopened.
GraphReader write_and_open(const testing::TempDir& dir, GraphInput input) {
  const auto path = dir / "g.mosb";
  write_graph(input, path);
  return GraphReader::open(path, VerifyLevel::full);
}

// Four arcs on a 2-vertex cycle, enough for correlations: 0→1, 1→0, 0→1, 1→0.
GraphInput four_arcs(std::vector<CostColumn> costs) {
  GraphInput g;
  g.vertex_count = 2;
  g.tails = {0, 1, 0, 1};
  g.heads = {1, 0, 1, 0};
  g.costs = std::move(costs);
  return g;
}

double rho(const ArcGroupStats& s, std::size_t i, std::size_t j) {
  for (const auto& c : s.correlations)
    if (c.first == i && c.second == j) {
      REQUIRE(c.rho.has_value());
      return *c.rho;
    }
  FAIL("no pair");
  return 0;
}

}  // namespace

TEST_CASE("stats: anti-correlated, independent and constant columns") {
  testing::TempDir dir;
  // Sorted by tail, the stored arc order is input arcs 0, 2, 1, 3; statistics do not depend on it.
  const auto r = write_and_open(
      dir, four_arcs({integer_column("up", {1, 2, 3, 4}), integer_column("down", {4, 3, 2, 1}),
                      integer_column("a", {0, 0, 1, 1}), integer_column("b", {0, 1, 0, 1}),
                      integer_column("flat", {7, 7, 7, 7})}));
  const auto s = compute_stats(r);
  REQUIRE(s.all_arcs.objectives.size() == 5);
  REQUIRE(s.all_arcs.correlations.size() == 10);
  CHECK(s.all_arcs.arc_count == 4);
  CHECK(rho(s.all_arcs, 0, 1) == doctest::Approx(-1.0).epsilon(1e-15));
  CHECK(rho(s.all_arcs, 2, 3) == 0.0);  // every centred product is ±1/4 and they cancel exactly
  // up vs a: deviations (−1.5, −0.5, 0.5, 1.5)·(−½, −½, ½, ½): Σ = 2, Σx² = 5, Σy² = 1.
  CHECK(rho(s.all_arcs, 0, 2) == doctest::Approx(2 / std::sqrt(5.0)).epsilon(1e-15));
  for (const auto& c : s.all_arcs.correlations)
    if (c.second == 4) CHECK_FALSE(c.rho.has_value());
  const auto& flat = s.all_arcs.objectives[4];
  CHECK(flat.name == "flat");
  CHECK(*flat.min == 7);
  CHECK(*flat.mean == 7);
  CHECK(*flat.max == 7);
  const auto& up = s.all_arcs.objectives[0];
  CHECK(*up.min == 1);
  CHECK(*up.mean == 2.5L);
  CHECK(*up.max == 4);
  CHECK(up.type == format::ElementType::u8);
}

TEST_CASE("stats: float columns and a u64 column near 2^64 keep exact ranges and means") {
  testing::TempDir dir;
  const std::uint64_t big = ~std::uint64_t{0} - 1;
  auto input =
      four_arcs({CostColumn{"f", "", std::vector<double>{0.5, 1.25, 2.0, 0.25}, std::nullopt},
                 integer_column("big", {big, big, big, big - 4})});
  const auto r = write_and_open(dir, input);
  const auto s = objective_stats(r, {0, 1});
  CHECK(*s.objectives[0].min == 0.25L);
  CHECK(*s.objectives[0].max == 2.0L);
  CHECK(*s.objectives[0].mean == 1.0L);
  CHECK(static_cast<std::uint64_t>(*s.objectives[1].max) == big);
  CHECK(static_cast<std::uint64_t>(*s.objectives[1].min) == big - 4);
  // Σ = 4·big − 4 overflows 64 bits; the exact mean is big − 1.
  CHECK(static_cast<std::uint64_t>(*s.objectives[1].mean) == big - 1);
}

TEST_CASE("stats: self-loops, parallel arcs and degrees") {
  testing::TempDir dir;
  GraphInput g;
  g.vertex_count = 3;
  g.tails = {0, 0, 0, 1, 1, 1, 2};
  g.heads = {1, 1, 1, 1, 1, 0, 1};
  g.costs.push_back(integer_column("c", {1, 2, 3, 4, 5, 6, 7}));
  const auto s = compute_stats(write_and_open(dir, g));
  CHECK(s.self_loops == 2);     // 1→1 twice
  CHECK(s.parallel_arcs == 3);  // two extra 0→1, one extra 1→1; 2→1 repeats no arc of 2
  CHECK(s.vertex_count == 3);
  CHECK(s.arc_count == 7);
  CHECK(*s.out_degree.min == 1);
  CHECK(*s.out_degree.max == 3);
  CHECK(*s.out_degree.mean == doctest::Approx(7.0 / 3));
  CHECK(*s.in_degree.min == 0);  // nothing enters 2
  CHECK(*s.in_degree.max == 6);
}

TEST_CASE("stats: three strongly connected components") {
  testing::TempDir dir;
  GraphInput g;
  g.vertex_count = 6;  // {0,1,2} cycle → {3,4} cycle → {5}
  g.tails = {0, 1, 2, 2, 3, 4, 4};
  g.heads = {1, 2, 0, 3, 4, 3, 5};
  g.costs.push_back(integer_column("c", {1, 1, 1, 1, 1, 1, 1}));
  const auto r = write_and_open(dir, g);
  const auto scc = strongly_connected_components(r);
  CHECK(scc.count == 3);
  CHECK(scc.largest == 3);
  const auto s = compute_stats(r);
  CHECK(s.scc_count == 3);
  CHECK(*s.out_degree.min == 0);
  CHECK(*s.in_degree.max == 2);
}

TEST_CASE("stats: SCCs on a long path and a long cycle need no recursion") {
  testing::TempDir dir;
  constexpr std::uint32_t n = 300'000;
  GraphInput g;
  g.vertex_count = n;
  for (std::uint32_t v = 0; v + 1 < n; ++v) {
    g.tails.push_back(v);
    g.heads.push_back(v + 1);
  }
  g.costs.push_back(integer_column("c", std::vector<std::uint64_t>(g.tails.size(), 1)));
  {
    const auto scc = strongly_connected_components(write_and_open(dir, g));
    CHECK(scc.count == n);
    CHECK(scc.largest == 1);
  }
  g.tails.push_back(n - 1);
  g.heads.push_back(0);
  std::get<0>(g.costs[0].values).push_back(1);
  const auto scc = strongly_connected_components(write_and_open(dir, g));
  CHECK(scc.count == 1);
  CHECK(scc.largest == n);
}

TEST_CASE("stats: --by-kind groups arcs by the u8 arc data 'kind'") {
  testing::TempDir dir;
  GraphInput g;
  g.vertex_count = 2;
  g.tails = {0, 0, 0, 0, 1, 1, 1};
  g.heads = {1, 1, 1, 1, 0, 0, 0};
  g.costs.push_back(integer_column("x", {1, 2, 3, 4, 10, 20, 30}));
  g.costs.push_back(integer_column("y", {4, 3, 2, 1, 10, 20, 30}));
  g.arc_data.push_back(DataColumn::from<std::uint8_t>("kind", 1, {0, 0, 0, 0, 1, 1, 1}));
  const auto r = write_and_open(dir, g);
  const auto s = compute_stats(r, {ViewChoice{}, true});
  REQUIRE(s.by_kind.size() == 2);
  CHECK(s.by_kind[0].kind == 0);
  CHECK(s.by_kind[0].stats.arc_count == 4);
  CHECK(rho(s.by_kind[0].stats, 0, 1) == doctest::Approx(-1.0));
  CHECK(s.by_kind[1].kind == 1);
  CHECK(s.by_kind[1].stats.arc_count == 3);
  CHECK(rho(s.by_kind[1].stats, 0, 1) == doctest::Approx(1.0));
  CHECK(*s.by_kind[1].stats.objectives[0].mean == 20);
  CHECK(rho(s.all_arcs, 0, 1) > 0.9);  // the kind-1 block dominates the pooled correlation

  testing::TempDir other;
  g.arc_data.clear();
  const auto plain = write_and_open(other, g);
  CHECK_THROWS_WITH_AS(compute_stats(plain, {ViewChoice{}, true}),
                       doctest::Contains("no arc data section 'kind'"), Error);
}

TEST_CASE("stats: a view selects and orders objectives") {
  testing::TempDir dir;
  auto input = four_arcs({integer_column("c1", {1, 2, 3, 4}), integer_column("c2", {4, 3, 2, 1}),
                          integer_column("c3", {1, 1, 2, 2})});
  input.metadata.set("view.pair.objectives", "c3,c1");
  const auto r = write_and_open(dir, input);
  const auto s = compute_stats(r, {ViewChoice{"pair", {}, {}}, false});
  REQUIRE(s.all_arcs.objectives.size() == 2);
  CHECK(s.all_arcs.objectives[0].name == "c3");
  CHECK(s.all_arcs.objectives[1].name == "c1");
  REQUIRE(s.all_arcs.correlations.size() == 1);
  CHECK(rho(s.all_arcs, 0, 1) == doctest::Approx(2 / std::sqrt(5.0)));
  CHECK_THROWS_WITH_AS(compute_stats(r, {ViewChoice{"nope", {}, {}}, false}),
                       doctest::Contains("no view 'nope' (views: pair)"), Error);
  // The same objective list without a view: no edit of the instance is needed.
  const auto listed = compute_stats(r, {ViewChoice{{}, {"c3", "c1"}, {}}, false});
  REQUIRE(listed.all_arcs.objectives.size() == 2);
  CHECK(listed.all_arcs.objectives[0].name == "c3");
  CHECK(rho(listed.all_arcs, 0, 1) == doctest::Approx(2 / std::sqrt(5.0)));
  CHECK_THROWS_WITH_AS(compute_stats(r, {ViewChoice{{}, {"c9"}, {}}, false}),
                       doctest::Contains("no objective named 'c9'"), Error);
}

TEST_CASE("stats: an empty graph has undefined ranges and degrees") {
  testing::TempDir dir;
  GraphInput g;
  g.costs.push_back(integer_column("c", {}));
  g.costs.push_back(integer_column("d", {}));
  const auto s = compute_stats(write_and_open(dir, g));
  CHECK(s.arc_count == 0);
  CHECK(s.scc_count == 0);
  CHECK_FALSE(s.out_degree.min.has_value());
  CHECK_FALSE(s.all_arcs.objectives[0].mean.has_value());
  CHECK_FALSE(s.all_arcs.correlations[0].rho.has_value());
}

TEST_CASE("stats: payload walkers refuse a reader opened without verification") {
  testing::TempDir dir;
  GraphInput g;
  g.vertex_count = 2;
  g.tails = {0};
  g.heads = {1};
  g.costs.push_back(integer_column("c", {1}));
  write_and_open(dir, g);
  const auto plain = GraphReader::open(dir / "g.mosb");
  CHECK_THROWS_WITH_AS(compute_stats(plain), doctest::Contains("GraphReader::open(path, level)"),
                       Error);
  CHECK_THROWS_AS(count_loops_and_parallel_arcs(plain), Error);
  CHECK_THROWS_AS(strongly_connected_components(plain), Error);
}
