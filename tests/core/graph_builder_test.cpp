#include "mosb/graph_builder.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "temp_dir.hpp"

using namespace mosb;
using format::ElementType;
using format::SectionKind;

namespace {

// 5 vertices, arcs deliberately out of tail order, with a parallel pair (1->2 twice) and a loop
// (3->3).
GraphInput small_graph() {
  GraphInput g;
  g.vertex_count = 5;
  g.tails = {3, 1, 0, 1, 3, 0, 1, 4};
  g.heads = {3, 2, 1, 2, 0, 4, 0, 1};
  g.metadata.set("benchmark", "small");
  return g;
}

template <class T>
std::vector<T> iota_values(std::size_t count, T first) {
  std::vector<T> v(count);
  for (std::size_t i = 0; i < count; ++i) v[i] = static_cast<T>(first + static_cast<T>(i));
  return v;
}

template <class T>
void check_vertex_column(const GraphReader& r, const std::string& name,
                         const std::vector<T>& expected) {
  const Section* s = r.find(SectionKind::vertex_data, name);
  REQUIRE(s != nullptr);
  CHECK(s->type == format::element_type_of<T>());
  auto values = r.values<T>(*s);
  CHECK(std::equal(values.begin(), values.end(), expected.begin(), expected.end()));
}

}  // namespace

TEST_CASE("the builder writes a stable forward CSR and its exact transpose") {
  testing::TempDir dir;
  auto g = small_graph();
  g.costs.push_back({"c", "", std::vector<std::uint64_t>{30, 11, 0, 12, 31, 1, 13, 40}, {}});
  write_graph(g, dir / "g.mosb");
  auto r = GraphReader::open(dir / "g.mosb");
  CHECK(r.vertex_count() == 5);
  CHECK(r.arc_count() == 8);
  auto off = r.forward_offsets();
  auto tgt = r.forward_targets();
  CHECK(std::vector<std::uint64_t>(off.begin(), off.end()) ==
        std::vector<std::uint64_t>{0, 2, 5, 5, 7, 8});
  // Vertex 1 keeps its input order 2, 2, 0; vertex 3 keeps 3, 0.
  CHECK(std::vector<std::uint32_t>(tgt.begin(), tgt.end()) ==
        std::vector<std::uint32_t>{1, 4, 2, 2, 0, 3, 0, 1});
  // The cost column travels with its arcs: arc ids 0.. now carry 0,1 | 11,12,13 | 30,31 | 40.
  auto c = r.cost<std::uint8_t>(0);
  CHECK(std::vector<int>(c.begin(), c.end()) == std::vector<int>{0, 1, 11, 12, 13, 30, 31, 40});
  // Reverse: in-arcs of 0 are arcs 4 (1->0) and 6 (3->0); of 2 are 2, 3.
  auto roff = r.reverse_offsets();
  auto rsrc = r.reverse_sources();
  auto rarc = r.reverse_arcs();
  CHECK(std::vector<std::uint64_t>(roff.begin(), roff.end()) ==
        std::vector<std::uint64_t>{0, 2, 4, 6, 7, 8});
  CHECK(std::vector<std::uint32_t>(rarc.begin(), rarc.end()) ==
        std::vector<std::uint32_t>{4, 6, 0, 7, 2, 3, 5, 1});
  CHECK(std::vector<std::uint32_t>(rsrc.begin(), rsrc.end()) ==
        std::vector<std::uint32_t>{1, 3, 0, 4, 1, 1, 3, 0});
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
}

TEST_CASE("every cost element type round-trips, chosen narrowest or forced") {
  testing::TempDir dir;
  auto g = small_graph();
  const std::vector<std::uint64_t> ones(8, 1);
  auto column = [&](std::string name, auto values, std::optional<ElementType> forced = {}) {
    g.costs.push_back({std::move(name), "u", std::move(values), forced});
  };
  column("u8", std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6, 255});
  column("u16", std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6, 256});
  column("u32", std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6, 65536});
  column("u64", std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6, 1ULL << 40});
  column("f32", std::vector<double>{0.5, 1.25, 2, 3, 4, 5, 6, 1e10});
  column("f64", std::vector<double>{0.1, 1.25, 2, 3, 4, 5, 6, 7});
  column("forced_u32", ones, ElementType::u32);
  column("forced_f64", ones, ElementType::f64);
  column("forced_u16_from_reals", std::vector<double>{1, 2, 3, 4, 5, 6, 7, 65535},
         ElementType::u16);
  write_graph(g, dir / "types.mosb");
  auto r = GraphReader::open(dir / "types.mosb");
  const ElementType expected[] = {ElementType::u8,  ElementType::u16, ElementType::u32,
                                  ElementType::u64, ElementType::f32, ElementType::f64,
                                  ElementType::u32, ElementType::f64, ElementType::u16};
  REQUIRE(r.objective_count() == std::size(expected));
  for (std::size_t i = 0; i < r.objective_count(); ++i) CHECK(r.objective(i).type == expected[i]);

  // Widening into a caller buffer restores the input values (in CSR order: arc 0 was input arc 2).
  std::vector<double> widened(8);
  r.read_cost_as(r.objective_index("u64"), widened);
  CHECK(widened[7] == double(1ULL << 40));
  r.read_cost_as(r.objective_index("f64"), widened);
  CHECK(widened[0] == 2);                     // input arc 2 (0->1) costs 2
  CHECK(widened[5] == doctest::Approx(0.1));  // input arc 0 (3->3) costs 0.1
  std::vector<std::uint64_t> integers(8);
  r.read_cost_as(r.objective_index("u16"), integers);
  CHECK(*std::max_element(integers.begin(), integers.end()) == 256);
  CHECK_THROWS_WITH_AS(r.read_cost_as(r.objective_index("f32"), integers),
                       doctest::Contains("do not convert to integers"), Error);
  CHECK(r.cost<float>("f32")[7] == 1e10f);
  CHECK(r.cost<std::uint64_t>("u64").size() == 8);
  CHECK_THROWS_WITH_AS((void)r.cost<std::uint32_t>("u8"),
                       doctest::Contains("holds u8 values, not u32"), Error);
  CHECK_THROWS_WITH_AS((void)r.cost<float>("nope"), doctest::Contains("no objective named 'nope'"),
                       Error);
  CHECK(r.metadata().get("objective.u8.unit") == "u");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
}

TEST_CASE("costs that do not fit their forced type, negative or non-finite costs are errors") {
  testing::TempDir dir;
  auto attempt = [&](CostColumn column) {
    auto g = small_graph();
    g.costs.push_back(std::move(column));
    write_graph(g, dir / "bad.mosb");
  };
  CHECK_THROWS_WITH_AS(
      attempt({"c", "", std::vector<std::uint64_t>(8, 256), ElementType::u8}),
      doctest::Contains("objective 'c', arc 0: cost 256 is not exactly representable as u8"),
      Error);
  CHECK_THROWS_WITH_AS(attempt({"c", "", std::vector<double>(8, 0.5), ElementType::u32}),
                       doctest::Contains("not exactly representable as u32"), Error);
  CHECK_THROWS_WITH_AS(attempt({"c", "", std::vector<double>(8, 0.1), ElementType::f32}),
                       doctest::Contains("not exactly representable as f32"), Error);
  CHECK_THROWS_WITH_AS(attempt({"c", "", std::vector<std::uint64_t>(8, 1), ElementType::i32}),
                       doctest::Contains("is not unsigned or float"), Error);
  CHECK_THROWS_WITH_AS(attempt({"c", "", std::vector<double>{1, 1, 1, -1, 1, 1, 1, 1}, {}}),
                       doctest::Contains("arc 3: cost -1 is not a finite non-negative number"),
                       Error);
  CHECK_THROWS_WITH_AS(attempt({"c", "", std::vector<double>{1, NAN, 1, 1, 1, 1, 1, 1}, {}}),
                       doctest::Contains("arc 1: cost nan"), Error);
  CHECK_THROWS_WITH_AS(attempt({"c", "", std::vector<std::uint64_t>(7, 1), {}}),
                       doctest::Contains("has 7 costs for 8 arcs"), Error);
  CHECK_FALSE(std::filesystem::exists(dir / "bad.mosb"));
}

TEST_CASE("vertex data of every element type, arc data and query sets round-trip") {
  testing::TempDir dir;
  auto g = small_graph();
  g.costs.push_back({"c", "", std::vector<std::uint64_t>(8, 1), {}});
  const auto u8 = iota_values<std::uint8_t>(5, 250);
  const auto u16 = iota_values<std::uint16_t>(5, 65530);
  const auto u32 = iota_values<std::uint32_t>(5, 4000000000u);
  const auto u64 = iota_values<std::uint64_t>(5, 1ULL << 60);
  const auto i8 = iota_values<std::int8_t>(5, -128);
  const auto i16 = iota_values<std::int16_t>(5, -32768);
  const auto i32 = iota_values<std::int32_t>(5, -73000000);
  const auto i64 = iota_values<std::int64_t>(5, -(1LL << 50));
  const std::vector<float> f32 = {0.5f, -1.5f, 3.25f, 1e-30f, 7};
  const std::vector<double> coords = {-73.9, 40.7, -74.0, 40.8, -73.5, 40.6, -73.6, 40.5, 0, 0};
  g.vertex_data = {DataColumn::from("u8", 1, u8),   DataColumn::from("u16", 1, u16),
                   DataColumn::from("u32", 1, u32), DataColumn::from("u64", 1, u64),
                   DataColumn::from("i8", 1, i8),   DataColumn::from("i16", 1, i16),
                   DataColumn::from("i32", 1, i32), DataColumn::from("i64", 1, i64),
                   DataColumn::from("f32", 1, f32), DataColumn::from("coords", 2, coords)};
  // Arc data is given in input order; the file holds it in CSR order.
  const std::vector<std::uint8_t> kind = {10, 11, 12, 13, 14, 15, 16, 17};
  g.arc_data = {DataColumn::from("kind", 1, kind)};
  g.queries = {{"default", {{0, 4}, {4, 0}, {2, 2}}}, {"empty", {}}};
  g.metadata.set("view.X.objectives", "c");
  g.metadata.set("view.X.queries", "default");
  write_graph(g, dir / "data.mosb");
  auto r = GraphReader::open(dir / "data.mosb");
  check_vertex_column(r, "u8", u8);
  check_vertex_column(r, "u16", u16);
  check_vertex_column(r, "u32", u32);
  check_vertex_column(r, "u64", u64);
  check_vertex_column(r, "i8", i8);
  check_vertex_column(r, "i16", i16);
  check_vertex_column(r, "i32", i32);
  check_vertex_column(r, "i64", i64);
  check_vertex_column(r, "f32", f32);
  check_vertex_column(r, "coords", coords);
  CHECK(r.find(SectionKind::vertex_data, "coords")->entry.row_width == 2);
  auto arc_kind = r.values<std::uint8_t>(*r.find(SectionKind::arc_data, "kind"));
  // CSR order of input arcs: 2, 5 | 1, 3, 6 | 0, 4 | 7.
  CHECK(std::vector<int>(arc_kind.begin(), arc_kind.end()) ==
        std::vector<int>{12, 15, 11, 13, 16, 10, 14, 17});
  auto q = r.queries("default");
  REQUIRE(q.size() == 3);
  CHECK(q[1] == Query{4, 0});
  CHECK(r.queries("empty").empty());
  CHECK_THROWS_WITH_AS((void)r.queries("other"), doctest::Contains("no query set named 'other'"),
                       Error);
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
}

TEST_CASE("an empty graph and a graph without arcs are valid") {
  testing::TempDir dir;
  GraphInput g;
  write_graph(g, dir / "empty.mosb");
  auto r = GraphReader::open(dir / "empty.mosb");
  CHECK(r.vertex_count() == 0);
  CHECK(r.forward_offsets().size() == 1);
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  g.vertex_count = 3;
  write_graph(g, dir / "isolated.mosb");
  CHECK_FALSE(verify(GraphReader::open(dir / "isolated.mosb"), VerifyLevel::full).has_value());
}

TEST_CASE("the builder rejects inconsistent input, naming what is wrong") {
  testing::TempDir dir;
  auto g = small_graph();
  g.heads[2] = 5;
  CHECK_THROWS_WITH_AS(
      write_graph(g, dir / "x.mosb"),
      doctest::Contains("arc 2 (0 -> 5) has an endpoint not below the vertex count 5"), Error);
  g = small_graph();
  g.queries = {{"q", {{0, 9}}}};
  CHECK_THROWS_WITH_AS(write_graph(g, dir / "x.mosb"), doctest::Contains("query set 'q', query 0"),
                       Error);
  g = small_graph();
  g.metadata.set("view.V.objectives", "missing");
  CHECK_THROWS_WITH_AS(write_graph(g, dir / "x.mosb"),
                       doctest::Contains("names objective 'missing'"), Error);
  g = small_graph();
  g.costs.push_back(
      {"a name that is far too long for a section", "", std::vector<std::uint64_t>(8, 1), {}});
  CHECK_THROWS_WITH_AS(write_graph(g, dir / "x.mosb"), doctest::Contains("must be 1-24 characters"),
                       Error);
  CHECK(std::filesystem::is_empty(dir.path()));
}

TEST_CASE("the content digest ignores layout but covers content") {
  testing::TempDir dir;
  auto g = small_graph();
  g.costs.push_back({"c", "", std::vector<std::uint64_t>(8, 1), {}});
  write_graph(g, dir / "a.mosb");
  write_graph(g, dir / "b.mosb");
  std::get<0>(g.costs[0].values)[3] = 2;
  write_graph(g, dir / "c.mosb");
  const auto a = GraphReader::open(dir / "a.mosb").digest();
  CHECK(a.size() == 32);
  CHECK(a == GraphReader::open(dir / "b.mosb").digest());
  CHECK(a != GraphReader::open(dir / "c.mosb").digest());
}
