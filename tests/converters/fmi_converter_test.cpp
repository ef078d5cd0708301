#include "mosb/converters/fmi_converter.hpp"

#include <doctest/doctest.h>

#include <cstdlib>
#include <deque>
#include <fstream>
#include <map>
#include <string>

#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "requirements.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;
using converters::FmiOptions;

namespace {

using namespace mosb::testing;  // write_text, slurp

// OsmGraphCreator's maxspeed layout: 4 nodes, 5 edges `src trg cost type maxspeed`.
const char* kMaxspeed =
    "# Id : 0\n"
    "# Timestamp : 0\n"
    "# Type : maxspeed\n"
    "# Revision: 1\n"
    "\n"
    "4\n"
    "5\n"
    "0 100 48.5 9.25 300\n"
    "1 101 48.51 9.26 310\n"
    "2 102 48.52 9.27 305\n"
    "3 9000000000 -33.5 -70.75 -2\n"
    "0 1 120 3 50\n"
    "1 2 80 4 30\n"
    "0 2 250 3 50\n"
    "2 3 40 7 0\n"
    "3 0 1000 1 120\n";

// The same graph: CRLF, comments and blank lines between data lines, tabs, no final newline.
const char* kMaxspeedMessy =
    "# Id : 0\r\n"
    "# Type : maxspeed\r\n"
    "\r\n"
    "4\t\r\n"
    "# a comment between the counts\r\n"
    "5\r\n"
    "0 100 48.5 9.25 300\r\n"
    "1\t101 48.51 9.26 310\r\n"
    "\r\n"
    "2 102 48.52 9.27 305 \r\n"
    "3 9000000000 -33.5 -70.75 -2\r\n"
    "0 1 120 3 50\r\n"
    "1 2 80 4 30\r\n"
    "#\r\n"
    "0 2 250 3 50\r\n"
    "2 3 40 7 0\r\n"
    "3 0 1000 1 120";

// Ten costs per edge (GER_10); elevations with a decimal.
const char* kTenCosts =
    "# ten costs\n"
    "\n"
    "3\n"
    "2\n"
    "0 7 48.1 9.1 250.5\n"
    "1 8 48.2 9.2 251\n"
    "2 9 48.3 9.3 252\n"
    "0 1 1 2 3 4 5 6 7 8 9 10\n"
    "1 2 10.5 0 0 1 0 0 0.25 3 1 0\n";

// A one-way street 3 -> 5; vertex 4 only has an out-arc into the rest; 2 and 7 lie beyond 6.
const char* kOneWay =
    "8\n"
    "11\n"
    "0 10 48.00 9.00 1\n"
    "1 11 48.01 9.01 2\n"
    "2 12 48.02 9.02 3\n"
    "3 13 48.03 9.03 4\n"
    "4 14 48.04 9.04 5\n"
    "5 15 48.05 9.05 6\n"
    "6 16 48.06 9.06 7\n"
    "7 17 48.07 9.07 8\n"
    "3 1 1 1\n"
    "1 3 11 1\n"
    "3 5 21 2\n"
    "5 6 31 2\n"
    "6 5 41 2\n"
    "1 0 51 3\n"
    "0 1 61 3\n"
    "6 2 71 4\n"
    "2 7 81 4\n"
    "4 3 91 5\n"
    "7 2 101 4\n";

FmiOptions fmi(const std::filesystem::path& file) {
  FmiOptions o;
  o.file = file.string();
  return o;
}

GraphReader convert(const FmiOptions& o, const std::filesystem::path& out) {
  write_graph(converters::convert_fmi(o), out);
  return GraphReader::open(out);
}

std::vector<double> costs(const GraphReader& r, std::size_t j) {
  std::vector<double> c(r.arc_count());
  r.read_cost_as(j, c);
  return c;
}

template <class T>
std::vector<T> vertex_data(const GraphReader& r, const char* name) {
  const auto* s = r.find(format::SectionKind::vertex_data, name);
  REQUIRE(s != nullptr);
  const auto v = r.values<T>(*s);
  return {v.begin(), v.end()};
}

template <class T>
std::vector<T> arc_data(const GraphReader& r, const char* name) {
  const auto* s = r.find(format::SectionKind::arc_data, name);
  REQUIRE(s != nullptr);
  const auto v = r.values<T>(*s);
  return {v.begin(), v.end()};
}

std::vector<std::uint32_t> targets(const GraphReader& r) {
  const auto t = r.forward_targets();
  return {t.begin(), t.end()};
}

std::vector<std::uint64_t> offsets(const GraphReader& r) {
  const auto o = r.forward_offsets();
  return {o.begin(), o.end()};
}

std::map<std::string, std::uint64_t> checksums(const GraphReader& r) {
  std::map<std::string, std::uint64_t> out;
  for (const auto& s : r.sections())
    if (s.name != "metadata") out[s.name] = s.entry.checksum;
  return out;
}

// Whether `goal` is reachable from `start` along forward arcs.
bool reachable(const GraphReader& r, std::uint32_t start, std::uint32_t goal) {
  const auto off = r.forward_offsets();
  const auto tgt = r.forward_targets();
  std::vector<bool> seen(r.vertex_count(), false);
  std::deque<std::uint32_t> queue{start};
  seen[start] = true;
  while (!queue.empty()) {
    const auto v = queue.front();
    queue.pop_front();
    if (v == goal) return true;
    for (auto a = off[v]; a < off[v + 1]; ++a)
      if (!seen[tgt[a]]) {
        seen[tgt[a]] = true;
        queue.push_back(tgt[a]);
      }
  }
  return false;
}

void check_parse_error(const std::string& text, const std::string& message,
                       std::optional<unsigned> cost_count = std::nullopt) {
  CAPTURE(text);
  CHECK_THROWS_WITH_AS(converters::parse_fmi(text, "t.fmi", cost_count), message.c_str(), Error);
}

}  // namespace

TEST_CASE(
    "fmi: the maxspeed layout converts with costs, type, maxspeed, coords, elevation, osm ids") {
  testing::TempDir dir;
  write_text(dir / "bw.fmi.txt", kMaxspeed);
  auto r = convert(fmi(dir / "bw.fmi.txt"), dir / "bw.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  CHECK(r.vertex_count() == 4);
  CHECK(r.arc_count() == 5);
  REQUIRE(r.objective_count() == 1);
  CHECK(r.objective(0).name == "c1");
  CHECK(r.objective(0).type == format::ElementType::u16);
  CHECK(offsets(r) == std::vector<std::uint64_t>{0, 2, 3, 4, 5});
  CHECK(targets(r) == std::vector<std::uint32_t>{1, 2, 2, 3, 0});
  CHECK(costs(r, 0) == std::vector<double>{120, 250, 80, 40, 1000});
  CHECK(arc_data<std::uint8_t>(r, "type") == std::vector<std::uint8_t>{3, 3, 4, 7, 1});
  CHECK(arc_data<std::uint8_t>(r, "maxspeed") == std::vector<std::uint8_t>{50, 50, 30, 0, 120});
  CHECK(vertex_data<double>(r, "coords") ==
        std::vector<double>{48.5, 9.25, 48.51, 9.26, 48.52, 9.27, -33.5, -70.75});
  CHECK(vertex_data<std::int32_t>(r, "elevation") == std::vector<std::int32_t>{300, 310, 305, -2});
  CHECK(vertex_data<std::uint64_t>(r, "osm_id") ==
        std::vector<std::uint64_t>{100, 101, 102, 9000000000});
  CHECK(r.find(format::SectionKind::vertex_data, "original_id") == nullptr);
  const auto& m = r.metadata();
  CHECK(m.get("benchmark") == "bw");
  CHECK(m.get("family") == "road");
  CHECK(m.get("id_base") == "0");
  CHECK(m.get("coords.order") == "lat,lon");
  CHECK(m.get("source.command") == "convert fmi");
  CHECK(m.get("source.input.0.name") == "bw.fmi.txt");
  CHECK(m.get("source.input.0.size") == std::to_string(std::string(kMaxspeed).size()));
  CHECK_FALSE(m.get("source.param.costs").has_value());

  SUBCASE("the standard layout has no maxspeed column") {
    write_text(dir / "std.txt", "2\n2\n0 1 0 0 0\n1 2 0 0 0\n0 1 5 300\n1 0 6 2\n");
    auto s = convert(fmi(dir / "std.txt"), dir / "std.mosb");
    CHECK(arc_data<std::uint16_t>(s, "type") == std::vector<std::uint16_t>{300, 2});
    CHECK(s.find(format::SectionKind::arc_data, "maxspeed") == nullptr);
  }
}

TEST_CASE(
    "fmi: CRLF, comments, blank lines and tabs change nothing but metadata, and output is "
    "deterministic") {
  testing::TempDir dir;
  write_text(dir / "plain.txt", kMaxspeed);
  write_text(dir / "messy.txt", kMaxspeedMessy);
  auto plain = convert(fmi(dir / "plain.txt"), dir / "plain.mosb");
  auto messy = convert(fmi(dir / "messy.txt"), dir / "messy.mosb");
  CHECK(checksums(plain).size() == 11);
  CHECK(checksums(plain) == checksums(messy));
  auto again = convert(fmi(dir / "plain.txt"), dir / "again.mosb");
  CHECK(slurp(dir / "plain.mosb") == slurp(dir / "again.mosb"));
  testing::require(std::system("command -v gzip >/dev/null 2>&1") == 0, "the 'gzip' command");
  REQUIRE(std::system(
              ("gzip -c '" + (dir / "plain.txt").string() + "' > '" + (dir / "p.gz").string() + "'")
                  .c_str()) == 0);
  auto packed = convert(fmi(dir / "p.gz"), dir / "packed.mosb");
  CHECK(checksums(packed) == checksums(plain));
}

TEST_CASE("fmi: ten costs get the GER_10 names in the paper's order") {
  testing::TempDir dir;
  write_text(dir / "ger.txt", kTenCosts);
  auto o = fmi(dir / "ger.txt");
  o.cost_count = 10;
  auto r = convert(o, dir / "ger.mosb");
  REQUIRE(r.objective_count() == 10);
  const std::vector<std::string> names = {"distance",     "time",        "ascent",    "large_roads",
                                          "medium_roads", "small_roads", "gas_price", "energy",
                                          "unit",         "quietness"};
  for (std::size_t j = 0; j < 10; ++j) CHECK(r.objective(j).name == names[j]);
  CHECK(format::is_float(r.objective(0).type));
  CHECK(r.objective(1).type == format::ElementType::u8);
  CHECK(costs(r, 0) == std::vector<double>{1, 10.5});
  CHECK(costs(r, 6) == std::vector<double>{7, 0.25});
  CHECK(costs(r, 9) == std::vector<double>{10, 0});
  CHECK(targets(r) == std::vector<std::uint32_t>{1, 2});
  CHECK(vertex_data<double>(r, "elevation") == std::vector<double>{250.5, 251, 252});
  CHECK(vertex_data<double>(r, "coords") == std::vector<double>{48.1, 9.1, 48.2, 9.2, 48.3, 9.3});
  CHECK(r.find(format::SectionKind::arc_data, "type") == nullptr);
  CHECK(r.metadata().get("source.param.costs") == "10");

  SUBCASE("trailing fields after the costs are skipped on request when every edge line has them") {
    write_text(dir / "skip.txt",
               "3\n2\n0 7 48.1 9.1 250.5\n1 8 48.2 9.2 251\n2 9 48.3 9.3 252\n"
               "0 1 1 2 3 4 5 6 7 8 9 10 -1 -1\n1 2 10.5 0 0 1 0 0 0.25 3 1 0 -1 -1\n");
    auto x = fmi(dir / "skip.txt");
    x.cost_count = 10;
    CHECK_THROWS_WITH_AS(converters::convert_fmi(x),
                         ((dir / "skip.txt").string() +
                          ":6:26: extra field '-1': an edge line is 'src trg' and 10 costs")
                             .c_str(),
                         Error);
    x.ignore_extra_fields = true;
    auto s = convert(x, dir / "skip.mosb");
    CHECK(checksums(s) == checksums(r));
    CHECK(s.metadata().get("source.param.ignore_extra_fields") == "1");
  }
  SUBCASE("named objectives must match the cost count") {
    o.cost_count = 2;
    CHECK_THROWS_WITH_AS(converters::convert_fmi(o),
                         ((dir / "ger.txt").string() +
                          ":8:9: extra field '3': an edge line is 'src trg' and 2 costs")
                             .c_str(),
                         Error);
    o.cost_count = 10;
    o.objectives = {{"distance", "m"}};
    CHECK_THROWS_WITH_AS(converters::convert_fmi(o),
                         ("convert fmi: 1 objective name given, " + (dir / "ger.txt").string() +
                          " has 10 cost columns")
                             .c_str(),
                         Error);
  }
}

TEST_CASE("fmi: malformed input gives FILE:LINE:COLUMN messages") {
  check_parse_error("# only a comment\n", "t.fmi:1:1: missing the node count");
  check_parse_error("x\n", "t.fmi:1:1: expected the node count, found 'x'");
  check_parse_error("3 4\n", "t.fmi:1:3: extra field '4' after the node count");
  check_parse_error("3\n", "t.fmi:1:1: missing the edge count");
  check_parse_error("3\n0\n0 0 0 0 0\n1 0 0 0 0\n",
                    "t.fmi:1:1: the header declares 3 nodes, found 2");
  check_parse_error("3\n1\n0 0 0 0 0\n2 0 0 0 0\n",
                    "t.fmi:4:1: expected node id 1 (ids 0..n-1 in order), found '2'");
  check_parse_error("1\n0\n0 0 48\n",
                    "t.fmi:3:7: missing field: a node line is 'id osm_id lat lon elevation'");
  check_parse_error("1\n0\n0 -4 1 2 3\n", "t.fmi:3:3: expected an OSM id, found '-4'");
  check_parse_error("1\n0\n0 0 91 0 0\n", "t.fmi:3:5: latitude '91' outside -90..90");
  check_parse_error("1\n0\n0 0 1 nan 0\n", "t.fmi:3:7: expected the longitude, found 'nan'");
  check_parse_error("1\n0\n0 0 1 2 x\n", "t.fmi:3:9: expected the elevation, found 'x'");
  const std::string two_nodes = "2\n1\n0 0 0 0 0\n1 0 0 0 0\n";
  check_parse_error("2\n2\n0 0 0 0 0\n1 0 0 0 0\n0 1 1 1\n",
                    "t.fmi:2:1: the header declares 2 edges, found 1");
  check_parse_error(two_nodes + "0 1 1 1\n1 0 1 1\n",
                    "t.fmi:6:1: the header declares 1 edge, found more");
  check_parse_error(two_nodes + "0 1 -5 1\n", "t.fmi:5:5: negative cost '-5'");
  check_parse_error(two_nodes + "0 1 5x 1\n", "t.fmi:5:5: expected a cost, found '5x'");
  check_parse_error(two_nodes + "0 2 5 1\n", "t.fmi:5:3: node id '2' outside 0..1");
  check_parse_error(two_nodes + "0 1 5\n",
                    "t.fmi:5:6: missing field: an edge line is 'src trg cost type [maxspeed]'");
  check_parse_error(two_nodes + "0 1 5 1 50 9\n",
                    "t.fmi:5:12: extra field '9': an edge line is 'src trg cost type [maxspeed]'");
  check_parse_error("2\n2\n0 0 0 0 0\n1 0 0 0 0\n0 1 5 1\n1 0 5 1 50\n",
                    "t.fmi:6:9: extra field '50': expected 4 fields as on line 5");
  check_parse_error(two_nodes + "0 1 5 -1\n", "t.fmi:5:7: expected the edge type, found '-1'");
  check_parse_error(two_nodes + "0 1 3 -5\n", "t.fmi:5:7: negative cost '-5'", 2);
  check_parse_error(two_nodes + "0 1 1 2\n",
                    "t.fmi:5:8: missing field: an edge line is 'src trg' and 3 costs", 3);
}

TEST_CASE("fmi: BFS extraction keeps the first N vertices in BFS order, remapped in id order") {
  testing::TempDir dir;
  write_text(dir / "oneway.txt", kOneWay);
  auto o = fmi(dir / "oneway.txt");
  o.extract_bfs = converters::FmiBfs{3, 5, false};
  auto r = convert(o, dir / "sub.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  // BFS from 3 along out-arcs: 3, then 1 and 5 (file order), then 0 (from 1), then 6 (from 5).
  CHECK(r.vertex_count() == 5);
  CHECK(vertex_data<std::uint32_t>(r, "original_id") == std::vector<std::uint32_t>{0, 1, 3, 5, 6});
  CHECK(vertex_data<std::uint64_t>(r, "osm_id") == std::vector<std::uint64_t>{10, 11, 13, 15, 16});
  CHECK(vertex_data<std::int32_t>(r, "elevation") == std::vector<std::int32_t>{1, 2, 4, 6, 7});
  CHECK(vertex_data<double>(r, "coords") ==
        std::vector<double>{48.00, 9.00, 48.01, 9.01, 48.03, 9.03, 48.05, 9.05, 48.06, 9.06});
  // Induced arcs (new ids 0,1,2,3,4 = old 0,1,3,5,6): 2->1, 1->2, 2->3, 3->4, 4->3, 1->0, 0->1.
  CHECK(r.arc_count() == 7);
  CHECK(offsets(r) == std::vector<std::uint64_t>{0, 1, 3, 5, 6, 7});
  CHECK(targets(r) == std::vector<std::uint32_t>{1, 2, 0, 1, 3, 4, 3});
  CHECK(costs(r, 0) == std::vector<double>{61, 11, 51, 1, 21, 31, 41});
  CHECK(arc_data<std::uint8_t>(r, "type") == std::vector<std::uint8_t>{3, 1, 3, 1, 2, 2, 2});
  // The one-way street survives: old 3 -> old 5 is connected, the reverse is not.
  CHECK(reachable(r, 2, 3));
  CHECK_FALSE(reachable(r, 3, 2));
  const auto& m = r.metadata();
  CHECK(m.get("source.param.extract_bfs_root") == "3");
  CHECK(m.get("source.param.extract_bfs_count") == "5");
  CHECK(m.get("source.param.bfs_undirected") == "0");

  SUBCASE("undirected BFS also follows in-arcs") {
    o.extract_bfs = converters::FmiBfs{3, 5, true};
    auto u = convert(o, dir / "undirected.mosb");
    // 3, then 1, 5, 4 (arcs 3->1, 1->3, 3->5, 4->3), then 0 (from 1).
    CHECK(vertex_data<std::uint32_t>(u, "original_id") ==
          std::vector<std::uint32_t>{0, 1, 3, 4, 5});
    CHECK(u.metadata().get("source.param.bfs_undirected") == "1");
  }
  SUBCASE("too few reachable vertices and a bad root are errors") {
    const auto name = (dir / "oneway.txt").string();
    o.extract_bfs = converters::FmiBfs{7, 8, false};
    CHECK_THROWS_WITH_AS(
        converters::convert_fmi(o),
        (name + ": BFS from vertex 7 reaches only 2 vertices, extract_bfs.count asks for 8")
            .c_str(),
        Error);
    o.extract_bfs = converters::FmiBfs{8, 1, false};
    CHECK_THROWS_WITH_AS(converters::convert_fmi(o),
                         (name + ": BFS root 8 is not a vertex (the graph has 8 vertices)").c_str(),
                         Error);
  }
  SUBCASE("the whole reachable set is deterministic") {
    o.extract_bfs = converters::FmiBfs{4, 8, false};
    write_graph(converters::convert_fmi(o), dir / "a.mosb");
    write_graph(converters::convert_fmi(o), dir / "b.mosb");
    CHECK(slurp(dir / "a.mosb") == slurp(dir / "b.mosb"));
    CHECK(GraphReader::open(dir / "a.mosb").arc_count() == 11);
  }
}
