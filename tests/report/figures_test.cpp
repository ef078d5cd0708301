#include "mosb/report/figures.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "golden_input.hpp"
#include "mosb/converters/guards_converter.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/stats.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;

namespace {

// dir/g.mosb: a 4 x 3 map with a wall at (1, 1), converted with a second input of `text` given to
// the converter as `option` (exposure_file or guards_file); returns the conversion.
auto convert_small_map(const testing::TempDir& dir, const std::string& text,
                       std::optional<std::string> converters::GuardsOptions::*option) {
  testing::write_text(dir / "small.map", "type octile\nheight 3\nwidth 4\nmap\n....\n.@..\n....\n");
  testing::write_text(dir / "input.txt", text);
  converters::GuardsOptions o;
  o.map_file = (dir / "small.map").string();
  o.*option = (dir / "input.txt").string();
  auto converted = converters::convert_guards(o);
  write_graph(converted.graph, dir / "g.mosb");
  return converted;
}

}  // namespace

TEST_CASE("map_of: cells, walls and exposure of a GUARDS instance") {
  testing::TempDir dir;
  // Each cell's exposure given (the wall's value is ignored).
  convert_small_map(dir, "1 2 3 4\n5 0 6 7\n8 9 1 2\n", &converters::GuardsOptions::exposure_file);

  const auto reader = GraphReader::open(dir / "g.mosb", VerifyLevel::full);
  const auto plot = plots::map_of(reader, "exposure", 160);
  CHECK(plot.width == 4);
  CHECK(plot.height == 3);
  CHECK(plot.passable == std::vector<bool>{true, true, true, true,   //
                                           true, false, true, true,  //
                                           true, true, true, true});
  REQUIRE(plot.exposure.size() == 12);
  // The cost of an orthogonal move into a cell is the cell's exposure; the wall has none.
  const double expected[] = {1, 2, 3, 4, 5, NAN, 6, 7, 8, 9, 1, 2};
  for (std::size_t i = 0; i < 12; ++i)
    CHECK(std::isnan(plot.exposure[i]) == std::isnan(expected[i]));
  for (std::size_t i = 0; i < 12; ++i)
    if (!std::isnan(expected[i])) CHECK(plot.exposure[i] == expected[i]);
  CHECK(plots::map_of(reader, "no-such-objective", 160).exposure.empty());

  // A reader not verified in full is refused: the map walks the CSR.
  CHECK_THROWS_AS(plots::map_of(GraphReader::open(dir / "g.mosb"), "exposure", 160), Error);
  CHECK(plot.guards.empty());  // an exposure grid says nothing of where guards stand
}

TEST_CASE("map_of: the guards of metadata map.guards, refused when malformed or off the map") {
  testing::TempDir dir;
  auto converted =
      convert_small_map(dir, "0 0\n3 2 1.5\n", &converters::GuardsOptions::guards_file);
  const auto plot =
      plots::map_of(GraphReader::open(dir / "g.mosb", VerifyLevel::full), "exposure", 160);
  REQUIRE(plot.guards.size() == 2);
  CHECK((plot.guards[0].x == 0 && plot.guards[0].y == 0));
  CHECK((plot.guards[1].x == 3 && plot.guards[1].y == 2));
  for (const char* bad : {"4,0", "0,3", "1", "1,2,3", "a,1", "1,1;", ",1", "1,"}) {
    CAPTURE(bad);
    converted.graph.metadata.set("map.guards", bad);
    write_graph(converted.graph, dir / "bad.mosb");
    const auto reader = GraphReader::open(dir / "bad.mosb", VerifyLevel::full);
    CHECK_THROWS_WITH_AS(plots::map_of(reader, "exposure", 160),
                         doctest::Contains("metadata map.guards"), Error);
  }
}

// Issue 36 §1: map.width and map.height of a file that passes verify --level full, read strictly
// and checked against the instance before anything of the map's size is allocated.
TEST_CASE("map_of: the map's size parsed strictly and checked against the instance") {
  testing::TempDir dir;
  auto converted =
      convert_small_map(dir, "0 0\n", &converters::GuardsOptions::guards_file);  // 11 vertices
  const auto map_of = [&](const char* width, const char* height) {
    converted.graph.metadata.set("map.width", width);
    converted.graph.metadata.set("map.height", height);
    write_graph(converted.graph, dir / "m.mosb");
    return plots::map_of(GraphReader::open(dir / "m.mosb", VerifyLevel::full), "exposure", 160);
  };
  for (const char* bad : {"-5", "5x", "4294967301", "4294967296", "0", "", " 4", "+4", "04", "4.0",
                          "99999999999999999999"}) {
    CAPTURE(bad);
    CHECK_THROWS_WITH_AS(map_of(bad, "3"), doctest::Contains("metadata map.width '"), Error);
    CHECK_THROWS_WITH_AS(map_of("4", bad),
                         doctest::Contains("is not a whole number from 1 to 4294967295"), Error);
  }
  // Each side fits in 32 bits, their product does not fit a map; and fewer cells than vertices.
  CHECK_THROWS_WITH_AS(map_of("4294967295", "4294967295"),
                       doctest::Contains("more than the 4294967294 a map may have"), Error);
  CHECK_THROWS_WITH_AS(map_of("100000", "100000"),
                       doctest::Contains("10000000000 cells), more than"), Error);
  CHECK_THROWS_WITH_AS(map_of("2", "5"),
                       doctest::Contains("its 11 vertices do not fit a 2 x 5 map (10 cells)"),
                       Error);
  CHECK_THROWS_WITH_AS(map_of("3", "4"), doctest::Contains("lies outside the map"), Error);
  // A map of billions of cells, nearly all blocked, is drawn in squares from its 11 vertices:
  // nothing of its size is allocated.
  const auto huge = map_of("65536", "65535");
  CHECK(huge.block == 410);
  CHECK(huge.width == 160);
  CHECK(huge.height == 160);
  CHECK(huge.passable.size() == 160 * 160);
  CHECK(std::count(huge.passable.begin(), huge.passable.end(), true) == 0);  // 11 of 168,100
  CHECK(huge.guards.size() == 1);
  const auto exact = map_of("4", "3");
  CHECK(exact.block == 1);
  CHECK(std::count(exact.passable.begin(), exact.passable.end(), true) == 11);
}

TEST_CASE("map_of: vertex data 'cell' must give one cell of the map per vertex") {
  testing::TempDir dir;
  auto converted = convert_small_map(dir, "0 0\n", &converters::GuardsOptions::guards_file);
  auto& cells = converted.graph.vertex_data.front();
  REQUIRE(cells.name == "cell");
  const auto with_cells = [&](const DataColumn& column) {
    auto graph = converted.graph;
    graph.vertex_data = {column};
    write_graph(graph, dir / "c.mosb");
    return plots::map_of(GraphReader::open(dir / "c.mosb", VerifyLevel::full), "exposure", 160);
  };
  // Vertices 0 and 1 on one cell: a map counts each passable cell once.
  auto same = cells;
  same.bytes[4] = same.bytes[0], same.bytes[5] = same.bytes[1];  // vertex 1's x = vertex 0's
  CHECK_THROWS_WITH_AS(with_cells(same),
                       doctest::Contains("vertices 0 and 1 lie on the same cell (0, 0)"), Error);
  // One value per vertex where (x, y) pairs are needed: not read past its end.
  std::vector<std::uint16_t> single(11, 0);
  CHECK_THROWS_WITH_AS(with_cells(DataColumn::from("cell", 1, single)),
                       doctest::Contains("vertex data 'cell' is not one (x, y) pair"), Error);
  std::vector<std::uint8_t> narrow(22, 0);
  CHECK_THROWS_WITH_AS(with_cells(DataColumn::from("cell", 2, narrow)),
                       doctest::Contains("vertex data 'cell' is not one (x, y) pair"), Error);
}

TEST_CASE("correlation_of: the objectives' names, 1 on the diagonal, each pair's ρ both ways") {
  ArcGroupStats stats;
  for (const char* name : {"a", "b", "c"}) stats.objectives.emplace_back().name = name;
  stats.correlations = {{0, 1, 0.5}, {0, 2, std::nullopt}, {1, 2, -0.25}};
  const auto plot = plots::correlation_of(stats);
  CHECK(plot.names == std::vector<std::string>{"a", "b", "c"});
  REQUIRE(plot.rho.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) CHECK(plot.rho[i][i] == 1.0);
  CHECK(plot.rho[0][1] == 0.5);
  CHECK(plot.rho[1][0] == 0.5);
  CHECK_FALSE(plot.rho[0][2]);  // undefined: drawn "n/a"
  CHECK_FALSE(plot.rho[2][0]);
  CHECK(plot.rho[2][1] == -0.25);
}

TEST_CASE("degrees_of and objective_unit: read from the instance") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "g.mosb");
  const auto instance = GraphReader::open(dir / "g.mosb", VerifyLevel::full);
  // Out-degrees 2, 2, 2 and 1.
  CHECK(plots::degrees_of(instance).vertices_by_degree == std::vector<std::uint64_t>{0, 1, 3});
  CHECK(plots::objective_unit(instance, "distance") == "m");
  CHECK(plots::objective_unit(instance, "risk").empty());
  CHECK(plots::objective_unit(instance, "no-such-objective").empty());
}

TEST_CASE("front_rows, pair_points, front_of and cardinality_of: a query's front, its sets named") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "g.mosb");
  const auto instance = GraphReader::open(dir / "g.mosb", VerifyLevel::full);
  SolutionWriter boa(instance, "Small_2");  // the `default` set: 3 queries
  SolverInfo solver;
  solver.name = "boa";
  boa.set_solver(solver);
  boa.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25, 80, 3.75});
  boa.set_query(1, QueryStatus::solved, std::vector<double>{120, 7.5});
  boa.set_query(2, QueryStatus::timeout, std::vector<double>{});
  boa.write(dir / "boa.sol");
  SolutionWriter reference(instance, "Small_2");  // names no solver
  reference.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25});
  reference.write(dir / "ref.sol");
  const auto s = SolutionReader::open_verified(dir / "boa.sol");
  const auto r = SolutionReader::open_verified(dir / "ref.sol");

  const auto rows = plots::front_rows(s, 0);
  CHECK(rows == std::vector<std::vector<double>>{{60, 5.25}, {80, 3.75}});
  const auto swapped = plots::pair_points(rows, 1, 0);
  REQUIRE(swapped.size() == 2);
  CHECK((swapped[1].x == 3.75 && swapped[1].y == 80));
  CHECK_THROWS_WITH_AS(plots::front_rows(s, 2),
                       doctest::Contains("query 2 is timeout, not solved: no front to draw"),
                       Error);

  const auto front = plots::front_of(s, &r, &instance, 0, 0, 1);
  CHECK(front.x_label == "distance");
  CHECK(front.y_label == "time");
  CHECK(front.x_unit == "m");
  CHECK(front.y_unit == "s");
  CHECK(front.objective_count == 2);
  CHECK(front.solution.size() == 2);
  CHECK(front.reference.size() == 1);
  CHECK(front.solver_name == "boa");
  CHECK(front.reference_name == "reference");  // the reference names no solver
  const auto alone = plots::front_of(r, nullptr, nullptr, 0, 1, 0);
  CHECK(alone.x_label == "time");
  CHECK(alone.x_unit.empty());
  CHECK(alone.solver_name == "solver");
  CHECK(alone.reference.empty());
  // The reference's query 1 is not run: no front, and the error says so.
  CHECK_THROWS_WITH_AS(plots::front_of(s, &r, nullptr, 1, 0, 1),
                       doctest::Contains("query 1 is not-run"), Error);

  auto cardinality = plots::cardinality_of(s);
  CHECK(cardinality.sizes == std::vector<std::uint64_t>{2, 1});
  CHECK(cardinality.left_out == 1);
  cardinality.title = "boa";
  CHECK(plots::plot_cardinality(cardinality).find("boa (1 unsolved query left out)") !=
        std::string::npos);
}
