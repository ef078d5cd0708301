#include "mosb/report/figures.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "mosb/converters/guards_converter.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
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
  const auto plot = plots::map_of(reader, "exposure");
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
  CHECK(plots::map_of(reader, "no-such-objective").exposure.empty());

  // A reader not verified in full is refused: the map walks the CSR.
  CHECK_THROWS_AS(plots::map_of(GraphReader::open(dir / "g.mosb"), "exposure"), Error);
  CHECK(plot.guards.empty());  // an exposure grid says nothing of where guards stand
}

TEST_CASE("map_of: the guards of metadata map.guards, refused when malformed or off the map") {
  testing::TempDir dir;
  auto converted =
      convert_small_map(dir, "0 0\n3 2 1.5\n", &converters::GuardsOptions::guards_file);
  const auto plot = plots::map_of(GraphReader::open(dir / "g.mosb", VerifyLevel::full), "exposure");
  REQUIRE(plot.guards.size() == 2);
  CHECK((plot.guards[0].x == 0 && plot.guards[0].y == 0));
  CHECK((plot.guards[1].x == 3 && plot.guards[1].y == 2));
  for (const char* bad : {"4,0", "0,3", "1", "1,2,3", "a,1", "1,1;", ",1", "1,"}) {
    CAPTURE(bad);
    converted.graph.metadata.set("map.guards", bad);
    write_graph(converted.graph, dir / "bad.mosb");
    const auto reader = GraphReader::open(dir / "bad.mosb", VerifyLevel::full);
    CHECK_THROWS_WITH_AS(plots::map_of(reader, "exposure"),
                         doctest::Contains("metadata map.guards"), Error);
  }
}
