// DIMACS-Extended: derived columns on a hand-made graph with hand-computed values, the elevation
// parser's located errors, and view metadata.
#include "mosb/converters/dimacs_extended.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <string>

#include "mosb/converters/dimacs_converter.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;
using converters::AvgOutdegreeMode;
using converters::ExtendedOptions;

namespace {

using namespace mosb::testing;  // write_text

// Out-degrees 3, 2, 1, 1: vertex 1 has a parallel pair to 2, vertex 2 a loop.
const char* kGraph =
    "p sp 4 7\n"
    "a 1 2 3\n"
    "a 2 3 4\n"
    "a 1 3 9\n"
    "a 3 4 1\n"
    "a 4 1 2\n"
    "a 1 2 5\n"
    "a 2 2 7\n";

const char* kElevation =
    "c elevations in metres\n"
    "p aux sp elev 4\n"
    "v 1 100\n"
    "v 3 50\n"
    "v 2 -20\n"
    "v 4 50\n";

std::vector<std::uint64_t> column(const GraphReader& r, const std::string& name) {
  std::vector<std::uint64_t> out(r.arc_count());
  r.read_cost_as(r.objective_index(name), out);
  return out;
}

GraphReader extended(const testing::TempDir& dir, const ExtendedOptions& extra) {
  write_text(dir / "g.gr", kGraph);
  write_text(dir / "g.elev", kElevation);
  converters::DimacsOptions o;
  o.gr_files = {(dir / "g.gr").string()};
  auto graph = converters::convert_dimacs(o);
  converters::append_derived_columns(graph, extra, o.id_base);
  mosb::add_views(graph, extra.views);
  write_graph(graph, dir / "g.mosb");
  return GraphReader::open(dir / "g.mosb");
}

void check_elevation_error(const std::string& text, const std::string& message) {
  CAPTURE(text);
  CHECK_THROWS_WITH_AS(converters::parse_dimacs_elevation(text, "e.elev", 1, 2), message.c_str(),
                       Error);
}

}  // namespace

TEST_CASE(
    "dimacs-extended: elevation, avg_outdegree and hop follow the gr columns in a fixed order") {
  testing::TempDir dir;
  ExtendedOptions o;
  o.hop = true;
  o.avg_outdegree = true;
  o.elevation_file = (dir / "g.elev").string();
  const auto r = extended(dir, o);
  REQUIRE(r.objective_count() == 4);
  CHECK(r.objective(0).name == "c1");
  CHECK(r.objective(1).name == "elevation");
  CHECK(r.objective(2).name == "avg_outdegree");
  CHECK(r.objective(3).name == "hop");
  // Forward CSR order: 1->2, 1->3, 1->2, 2->3, 2->2, 3->4, 4->1.
  CHECK(column(r, "c1") == std::vector<std::uint64_t>{3, 9, 5, 4, 7, 1, 2});
  CHECK(column(r, "elevation") == std::vector<std::uint64_t>{120, 50, 120, 70, 0, 0, 50});
  CHECK(column(r, "avg_outdegree") == std::vector<std::uint64_t>{5, 4, 5, 3, 4, 2, 4});
  CHECK(column(r, "hop") == std::vector<std::uint64_t>{1, 1, 1, 1, 1, 1, 1});
  const auto& m = r.metadata();
  CHECK(m.get("source.param.derive") == "avg-outdegree,hop");
  CHECK(m.get("source.param.avg_outdegree") == "twice");
  CHECK(m.get("source.param.elevation") == "g.elev");
  CHECK(m.get("source.input.1.name") == "g.elev");
}

TEST_CASE("dimacs-extended: avg_outdegree rounded half up, and one derived column alone") {
  testing::TempDir dir;
  ExtendedOptions o;
  o.avg_outdegree = true;
  o.avg_outdegree_mode = AvgOutdegreeMode::round_half_up;
  const auto r = extended(dir, o);
  REQUIRE(r.objective_count() == 2);
  CHECK(column(r, "avg_outdegree") == std::vector<std::uint64_t>{3, 2, 3, 2, 2, 1, 2});
  CHECK(r.metadata().get("source.param.avg_outdegree") == "round-half-up");
  CHECK(converters::out_degrees(4, {0, 0, 1, 0}) == std::vector<std::uint32_t>{3, 1, 0, 0});
}

TEST_CASE("dimacs-extended: elevation files with errors give FILE:LINE:COLUMN") {
  check_elevation_error("v 1 3\n", "e.elev:1:1: 'v' line before the 'p aux sp elev n' line");
  check_elevation_error("p aux sp elev 3\n", "e.elev:1:15: declares 3 vertices, the graph has 2");
  check_elevation_error("p aux sp co 2\n", "e.elev:1:3: expected 'p aux sp elev n'");
  check_elevation_error("p aux sp elev 2\nv 1 5\nv 3 5\n",
                        "e.elev:3:3: vertex id '3' outside 1..2");
  check_elevation_error("p aux sp elev 2\nv 1 5\nv 1 6\n",
                        "e.elev:3:3: second 'v' line for vertex 1");
  check_elevation_error("p aux sp elev 2\nv 1 5\nv 2 1.5\n",
                        "e.elev:3:5: expected an integer elevation, found '1.5'");
  check_elevation_error("p aux sp elev 2\nv 1 5\nv 2\n",
                        "e.elev:3:4: missing field: an elevation line is 'v id elevation'");
  check_elevation_error("p aux sp elev 2\nv 1 5 6\n",
                        "e.elev:2:7: extra field '6': an elevation line is 'v id elevation'");
  check_elevation_error("p aux sp elev 2\nv 2 5\n", "e.elev:1:1: no 'v' line for vertex 1");
  check_elevation_error("c only\n", "e.elev:1:1: no 'p aux sp elev n' line");
  check_elevation_error("p aux sp elev 2\nx\n", "e.elev:2:1: unknown line type 'x'");
  const auto ok = converters::parse_dimacs_elevation(
      "p aux sp elev 2\r\nv 2 -9223372036854775808\nv 1 7", "e", 1, 2);
  CHECK(ok == std::vector<std::int64_t>{7, INT64_MIN});
}

TEST_CASE(
    "dimacs-extended: views record objectives and .queries only for a query set the file has") {
  testing::TempDir dir;
  ExtendedOptions o;
  o.hop = true;
  o.views = {mosb::parse_view_spec("NY_2=c1,hop"), mosb::parse_view_spec("only_hop=hop@q100")};
  const auto r = extended(dir, o);
  const auto& m = r.metadata();
  CHECK(m.get("view.NY_2.objectives") == "c1,hop");
  CHECK_FALSE(m.get("view.NY_2.queries").has_value());
  CHECK(m.get("view.only_hop.objectives") == "hop");
  CHECK_FALSE(m.get("view.only_hop.queries").has_value());
  CHECK(m.get("source.param.view.NY_2") == "c1,hop@default");
  CHECK(m.get("source.param.view.only_hop") == "hop@q100");

  GraphInput g;
  g.vertex_count = 2;
  g.tails = {0};
  g.heads = {1};
  g.costs.push_back({"c1", "", std::vector<std::uint64_t>{4}, std::nullopt});
  g.queries.push_back({"default", {{0, 1}}});
  mosb::add_views(g, {mosb::parse_view_spec("v=c1")});
  CHECK(g.metadata.get("view.v.queries") == "default");
  CHECK_NOTHROW(write_graph(g, dir / "q.mosb"));
  CHECK_THROWS_WITH_AS(mosb::add_views(g, {mosb::parse_view_spec("w=c1,c2")}),
                       "view 'w': objective 'c2' is not a column (columns: c1)", Error);
}

TEST_CASE("dimacs-extended: malformed --view texts are refused with one line") {
  CHECK_THROWS_WITH_AS(mosb::parse_view_spec("NY"),
                       "view 'NY': expected NAME=OBJ1,OBJ2,...[@QUERYSET]", Error);
  CHECK_THROWS_WITH_AS(mosb::parse_view_spec("=a"),
                       "view '=a': the view name must be 1 or more of [A-Za-z0-9_.+-]", Error);
  CHECK_THROWS_WITH_AS(mosb::parse_view_spec("v=a,,b"),
                       "view 'v=a,,b': empty or invalid objective name ''", Error);
  CHECK_THROWS_WITH_AS(mosb::parse_view_spec("v=a,a"), "view 'v=a,a': objective 'a' listed twice",
                       Error);
  CHECK_THROWS_WITH_AS(mosb::parse_view_spec("v=a@"),
                       "view 'v=a@': the query set name must be 1-24 characters "
                       "from [A-Za-z0-9_.+-]",
                       Error);
  const auto v = mosb::parse_view_spec("DIMACS-NY_2=distance,time@ny100");
  CHECK(v.name == "DIMACS-NY_2");
  CHECK(v.objectives == std::vector<std::string>{"distance", "time"});
  CHECK(v.queries == "ny100");
}
