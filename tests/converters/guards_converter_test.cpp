#include "mosb/converters/guards_converter.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <fstream>
#include <string>

#include "mosb/converters/movingai.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/random.hpp"
#include "mosb/verify.hpp"
#include "requirements.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;
using namespace mosb::converters;

namespace {

using namespace mosb::testing;  // write_text, slurp

std::string error_of(auto&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// 4 x 3, one wall cell at (1, 1).
const char* kSmall =
    "type octile\nheight 3\nwidth 4\nmap\n"
    "....\n"
    ".@..\n"
    "....\n";

// Guard A at (0, 0) unlimited, guard B at (3, 2) radius 1. A is hidden from every cell whose
// segment touches (1, 1), including (3, 1), whose segment passes exactly through the corner (2, 1).
const std::vector<std::uint64_t> kSmallExposure = {1, 1, 1, 1,  //
                                                   1, 0, 0, 1,  //
                                                   1, 0, 1, 1};

// Independent line-of-sight oracle: the closed segment against every blocked closed square in the
// bounding box (Liang-Barsky in exact integer fractions, coordinates doubled).
bool segment_touches_square(std::int64_t px, std::int64_t py, std::int64_t dx, std::int64_t dy,
                            std::int64_t i, std::int64_t j) {
  std::int64_t lo_num = 0, lo_den = 1, hi_num = 1, hi_den = 1;  // t in [lo, hi]
  const std::int64_t p[2] = {px, py}, d[2] = {dx, dy}, low[2] = {2 * i, 2 * j};
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0) {
      if (p[a] < low[a] || p[a] > low[a] + 2) return false;
      continue;
    }
    std::int64_t n1 = low[a] - p[a], n2 = low[a] + 2 - p[a], den = d[a];
    if (den < 0) n1 = -n1, n2 = -n2, den = -den;
    if (n1 > n2) std::swap(n1, n2);
    if (n1 * lo_den > lo_num * den) lo_num = n1, lo_den = den;
    if (n2 * hi_den < hi_num * den) hi_num = n2, hi_den = den;
  }
  return lo_num * hi_den <= hi_num * lo_den;
}

bool oracle_sees(const OctileMap& m, std::uint32_t x0, std::uint32_t y0, std::uint32_t x1,
                 std::uint32_t y1) {
  const std::int64_t px = 2 * std::int64_t{x0} + 1, py = 2 * std::int64_t{y0} + 1;
  const std::int64_t dx = 2 * (std::int64_t{x1} - x0), dy = 2 * (std::int64_t{y1} - y0);
  for (auto j = std::min(y0, y1); j <= std::max(y0, y1); ++j)
    for (auto i = std::min(x0, x1); i <= std::max(x0, x1); ++i)
      if (!m.is_passable(i, j) && segment_touches_square(px, py, dx, dy, i, j)) return false;
  return true;
}

// Legal moves counted per unordered direction pair, unlike the converter's per-tail loop.
std::uint64_t count_moves(const OctileMap& m) {
  std::uint64_t moves = 0;
  auto open = [&](std::uint32_t x, std::uint32_t y) { return m.is_passable(x, y); };
  for (std::uint32_t y = 0; y < m.height; ++y)
    for (std::uint32_t x = 0; x + 1 < m.width; ++x) moves += 2 * (open(x, y) && open(x + 1, y));
  for (std::uint32_t y = 0; y + 1 < m.height; ++y)
    for (std::uint32_t x = 0; x < m.width; ++x) moves += 2 * (open(x, y) && open(x, y + 1));
  for (std::uint32_t y = 0; y + 1 < m.height; ++y)
    for (std::uint32_t x = 0; x + 1 < m.width; ++x) {
      const bool square = open(x, y) && open(x + 1, y) && open(x, y + 1) && open(x + 1, y + 1);
      moves += square ? 4 : 0;  // both diagonals of a fully open 2x2 block, both directions
    }
  return moves;
}

}  // namespace

TEST_CASE("movingai: map parsing, CRLF, missing final newline, terrain") {
  const auto m =
      parse_octile_map("type octile\r\nheight 2\r\nwidth 3\r\nmap\r\n.GS\r\nW@T", "m.map");
  CHECK(m.width == 3);
  CHECK(m.height == 2);
  CHECK(m.passable == std::vector<std::uint8_t>{1, 1, 1, 0, 0, 0});
  const auto flipped =
      parse_octile_map("type octile\nwidth 3\nheight 2\nmap\n.GS\nW@O\n", "m.map", {false, true});
  CHECK(flipped.passable == std::vector<std::uint8_t>{1, 1, 0, 1, 0, 0});
}

TEST_CASE("movingai: map errors name FILE:LINE:COLUMN") {
  const std::string head = "type octile\nheight 2\nwidth 3\nmap\n";
  CHECK(error_of([&] { parse_octile_map(head + "...\n..\n", "m.map"); }) ==
        "m.map:6:3: row 2 has 2 cells, the map is 3 wide");
  CHECK(error_of([&] { parse_octile_map(head + "....\n...\n", "m.map"); }) ==
        "m.map:5:4: row 1 has 4 cells, the map is 3 wide");
  CHECK(error_of([&] { parse_octile_map(head + "...\n", "m.map"); }) ==
        "m.map:6:1: missing row 2 of 2");
  CHECK(error_of([&] { parse_octile_map(head + "...\n.x.\n", "m.map"); }) ==
        "m.map:6:2: unknown terrain character 'x'");
  CHECK(error_of([&] {
          parse_octile_map("type tile\n", "m.map");
        }).starts_with("m.map:1:6: expected 'type octile'"));
  CHECK(error_of([&] {
          parse_octile_map("type octile\nheight 100000\nwidth 100000\nmap\n", "m.map");
        }).starts_with("m.map:3:1: a 100000 x 100000 map cannot be held"));
  CHECK(error_of([&] {
          parse_octile_map(head + "...\n...\nextra\n", "m.map");
        }).starts_with("m.map:7:1: text after"));
}

TEST_CASE("guards: hand-checked exposure, a guard behind a wall, the radius rule") {
  const auto m = parse_octile_map(kSmall, "small.map");
  const auto guards = parse_guards("# A then B\n0 0\n3 2 1  # radius 1\n", "g.txt", m);
  REQUIRE(guards.size() == 2);
  CHECK(guards[1].radius_milli == 1000);
  CHECK(compute_exposure(m, guards) == kSmallExposure);
  CHECK_FALSE(line_of_sight(m, 0, 0, 3, 1));  // through the corner of the wall cell
  CHECK(line_of_sight(m, 0, 0, 3, 0));
  // (2, 1) is sqrt(2) from (3, 2): outside radius 1.414, inside 1.415.
  const auto near = compute_exposure(m, parse_guards("3 2 1.414\n", "g.txt", m));
  const auto far = compute_exposure(m, parse_guards("3 2 1.415\n", "g.txt", m));
  CHECK(near[1 * 4 + 2] == 0);
  CHECK(far[1 * 4 + 2] == 1);
  CHECK(error_of([&] { parse_guards("0 0\n1 1\n", "g.txt", m); }) ==
        "g.txt:2:1: guard on the blocked cell (1, 1)");
  CHECK(error_of([&] { parse_guards("4 0\n", "g.txt", m); }).starts_with("g.txt:1:1: guard x '4'"));
  CHECK(error_of([&] {
          parse_guards("0 0 1.2345\n", "g.txt", m);
        }).starts_with("g.txt:1:5: expected a radius"));
}

TEST_CASE("guards: line of sight agrees with an independent segment/square oracle") {
  auto rng = stream(2024, 0);
  for (int trial = 0; trial < 30; ++trial) {
    OctileMap m;
    m.width = 9;
    m.height = 7;
    m.passable.resize(63);
    for (auto& p : m.passable) p = rng.uniform(0, 99) < 75 ? 1 : 0;
    for (std::uint32_t a = 0; a < 63; ++a)
      for (std::uint32_t b = 0; b < 63; ++b) {
        const auto x0 = a % 9, y0 = a / 9, x1 = b % 9, y1 = b / 9;
        REQUIRE_MESSAGE(
            line_of_sight(m, x0, y0, x1, y1) == oracle_sees(m, x0, y0, x1, y1),
            "trial " << trial << " (" << x0 << "," << y0 << ")->(" << x1 << "," << y1 << ")");
      }
  }
}

TEST_CASE("guards: graph arcs and costs on the hand-made map") {
  const auto m = parse_octile_map(kSmall, "small.map");
  const auto g = materialize(build_guards_graph(m, kSmallExposure));
  CHECK(g.vertex_count == 11);
  CHECK(g.tails.size() == count_moves(m));
  auto arc = [&](std::uint32_t u,
                 std::uint32_t v) -> std::optional<std::pair<std::uint64_t, std::uint64_t>> {
    for (std::size_t k = 0; k < g.tails.size(); ++k)
      if (g.tails[k] == u && g.heads[k] == v)
        return std::pair{std::get<0>(g.costs[0].values)[k], std::get<0>(g.costs[1].values)[k]};
    return std::nullopt;
  };
  // Vertex ids: (0,0)=0 (1,0)=1 (2,0)=2 (3,0)=3 (0,1)=4 (2,1)=5 (3,1)=6 (0,2)=7 (1,2)=8 (2,2)=9
  // (3,2)=10.
  CHECK(arc(0, 1) == std::pair<std::uint64_t, std::uint64_t>{10, 1});
  CHECK(arc(6, 5) ==
        std::pair<std::uint64_t, std::uint64_t>{10, 0});  // orthogonal: destination only
  CHECK(arc(3, 5) == std::pair<std::uint64_t, std::uint64_t>{14, 1});  // diagonal: side cells count
  CHECK(arc(5, 10) == std::pair<std::uint64_t, std::uint64_t>{14, 1});
  CHECK_FALSE(arc(1, 4));  // diagonal past the wall corner
  CHECK_FALSE(arc(8, 5));
  CHECK_FALSE(arc(0, 9));  // not adjacent
}

TEST_CASE("guards: exposure file round trip, scenario import and errors, determinism") {
  testing::TempDir dir;
  write_text(dir / "small.map", kSmall);
  write_text(dir / "g.txt", "0 0\n3 2 1\n");
  write_text(dir / "small.scen",
             "version 1\n0\tsmall.map\t4\t3\t0\t0\t3\t2\t3.41421\n"
             "1\tsmall.map\t4\t3\t2\t1\t0\t2\t2.41421\n");
  GuardsOptions o;
  o.map_file = (dir / "small.map").string();
  o.guards_file = (dir / "g.txt").string();
  o.scen_file = (dir / "small.scen").string();
  const auto r = convert_guards(o);
  REQUIRE(r.graph.queries.size() == 1);
  CHECK(r.graph.queries[0].name == "scen");
  CHECK(r.graph.queries[0].pairs == std::vector<Query>{{0, 10}, {5, 7}});
  CHECK(r.graph.metadata.get("benchmark") == "small");
  CHECK(r.graph.metadata.get("view.Games-GUARDS_2.objectives") == "length,exposure");

  // The written grid read back as --exposure gives the same costs; blocked cells may hold anything.
  auto text = format_exposure(r.map, r.exposure);
  CHECK(text == "1 1 1 1\n1 0 0 1\n1 0 1 1\n");
  text.replace(text.find("1 0 0"), 5, "1 @@ 0");
  write_text(dir / "e.txt", text);
  GuardsOptions from_file = o;
  from_file.guards_file.reset();
  from_file.exposure_file = (dir / "e.txt").string();
  const auto r2 = convert_guards(from_file);
  CHECK(std::get<0>(materialize(r2.graph).costs[1].values) ==
        std::get<0>(materialize(r.graph).costs[1].values));

  write_graph(r.graph, dir / "a.mosb");
  write_graph(convert_guards(o).graph, dir / "b.mosb");
  CHECK(slurp(dir / "a.mosb") == slurp(dir / "b.mosb"));
  // Streamed from the map, the same bytes as the arc list held in memory.
  write_graph(materialize(r.graph), dir / "c.mosb");
  CHECK(slurp(dir / "a.mosb") == slurp(dir / "c.mosb"));
  CHECK_FALSE(verify(GraphReader::open(dir / "a.mosb"), VerifyLevel::full).has_value());

  const auto m = r.map;
  const auto scen = [&](const std::string& row) {
    return error_of([&] {
      check_scenario(parse_scenario("version 1\n" + row, "s.scen"), "s.scen", m, "small.map");
    });
  };
  CHECK(scen("0\tsmall.map\t4\t3\t1\t1\t0\t0\t1\n") ==
        "s.scen:2:17: the start cell (1, 1) is blocked in small.map");
  CHECK(scen("0\tsmall.map\t4\t3\t0\t0\t1\t1\t1\n") ==
        "s.scen:2:21: the goal cell (1, 1) is blocked in small.map");
  CHECK(scen("0\tsmall.map\t5\t3\t0\t0\t1\t0\t1\n")
            .starts_with("s.scen:2:13: the row gives a 5 x 3 map"));
  CHECK(scen("0\tsmall.map\t4\t3\t0\t0\t1\n").starts_with("s.scen:2:22: missing field"));
  CHECK(error_of([&] { parse_exposure("1 1 1 1\n1 x 0 1\n1 0 1\n", "e.txt", m); }) ==
        "e.txt:3:6: row 3 has 3 values, the map is 4 wide");
  CHECK(error_of([&] {
          parse_exposure("1 1 1 1\n1 x -1 1\n1 0 1 1\n", "e.txt", m);
        }).starts_with("e.txt:2:5: expected a non-negative integer"));
}

TEST_CASE("guards: real Moving AI maps (shared/data/movingai)") {
  const auto data = testing::shared_data() / "movingai";
  testing::require_shared(data / "arena2.map");
  const struct {
    const char* map;
    std::uint64_t scen_rows, scen_lines;
  } cases[] = {{"arena2.map", 929, 932}, {"random512-20-1.map", 1770, 1771}};
  for (const auto& c : cases) {
    CAPTURE(c.map);
    const auto text = slurp(data / c.map);
    const auto m = parse_octile_map(text, c.map);
    // Passable cells counted from the raw text, not from the parsed flags.
    std::uint64_t passable = 0;
    for (std::size_t pos = text.find("\nmap") + 4; pos < text.size(); ++pos)
      passable += text[pos] == '.';
    // A few fixed guards on passable cells: the first passable cell of rows h/4, h/2, 3h/4.
    std::string guards;
    for (std::uint32_t y : {m.height / 4, m.height / 2, 3 * m.height / 4})
      for (std::uint32_t x = 0; x < m.width; ++x)
        if (m.is_passable(x, y)) {
          guards += std::to_string(x) + " " + std::to_string(y) + " 40\n";
          break;
        }
    const auto exposure = compute_exposure(m, parse_guards(guards, "g.txt", m));
    const auto g = materialize(build_guards_graph(m, exposure));
    CHECK(g.vertex_count == passable);
    CHECK(g.tails.size() == count_moves(m));
    const auto scen_text = slurp(data / (std::string(c.map) + ".scen"));
    const auto entries = parse_scenario(scen_text, "s.scen");
    CHECK(entries.size() == c.scen_rows);
    // arena2.map.scen ends in 2 blank lines: 932 lines, 929 rows; random512-20-1: 1771 lines.
    const auto newlines =
        static_cast<std::uint64_t>(std::count(scen_text.begin(), scen_text.end(), '\n'));
    CHECK(newlines == c.scen_lines);
    check_scenario(entries, "s.scen", m, c.map);
  }
}
