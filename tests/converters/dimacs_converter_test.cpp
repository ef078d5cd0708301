#include "mosb/converters/dimacs_converter.hpp"

#include <doctest/doctest.h>
#include <xxhash.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <string>

#include "file_patch.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/verify.hpp"
#include "requirements.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;
using converters::DimacsOptions;

namespace {

using namespace mosb::testing;  // write_text, slurp

const char* kTwoCost =
    "c a hand-made graph: 4 vertices, 5 arcs, 2 cost columns\n"
    "p sp 4 5\n"
    "a 1 2 3 10\n"
    "a 2 3 4 20\n"
    "a 1 3 9 5\n"
    "a 3 4 1 300\n"
    "a 4 1 2 0\n";

// The same graph, with CRLF, comments, a bare `c`, blank lines, trailing blanks, no final newline.
const char* kTwoCostMessy =
    "c a hand-made graph\r\n"
    "\r\n"
    "c\r\n"
    "p sp 4 5 \t\r\n"
    "a 1 2 3 10\r\n"
    "c between arcs\r\n"
    "   \r\n"
    "a 2 3 4 20\t\r\n"
    "a 1 3 9 5\r\n"
    "\n"
    "a\t3 4 1  300\r\n"
    "a 4 1 2 0";

GraphReader convert(const DimacsOptions& o, const std::filesystem::path& out) {
  write_graph(converters::convert_dimacs(o), out);
  return GraphReader::open(out);
}

DimacsOptions gr(std::initializer_list<std::filesystem::path> files) {
  DimacsOptions o;
  for (const auto& f : files) o.gr_files.push_back(f.string());
  return o;
}

// Section checksums by name, the metadata section left out.
std::map<std::string, std::uint64_t> checksums(const GraphReader& r) {
  std::map<std::string, std::uint64_t> out;
  for (const auto& s : r.sections())
    if (s.name != "metadata") out[s.name] = s.entry.checksum;
  return out;
}

std::vector<double> costs(const GraphReader& r, std::size_t j) {
  std::vector<double> c(r.arc_count());
  r.read_cost_as(j, c);
  return c;
}

bool have_command(const std::string& name) {
  return std::system(("command -v " + name + " >/dev/null 2>&1").c_str()) == 0;
}

void check_parse_error(const std::string& text, const std::string& message, unsigned id_base = 1) {
  CAPTURE(text);
  CHECK_THROWS_WITH_AS(converters::parse_dimacs_gr(text, "t.gr", id_base), message.c_str(), Error);
}

}  // namespace

TEST_CASE("dimacs: a 2-objective graph converts with the right CSR and costs") {
  testing::TempDir dir;
  write_text(dir / "g.gr", kTwoCost);
  auto r = convert(gr({dir / "g.gr"}), dir / "g.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  CHECK(r.vertex_count() == 4);
  CHECK(r.arc_count() == 5);
  REQUIRE(r.objective_count() == 2);
  const auto off = r.forward_offsets();
  CHECK(std::vector<std::uint64_t>(off.begin(), off.end()) ==
        std::vector<std::uint64_t>{0, 2, 3, 4, 5});
  const auto tgt = r.forward_targets();
  CHECK(std::vector<std::uint32_t>(tgt.begin(), tgt.end()) ==
        std::vector<std::uint32_t>{1, 2, 2, 3, 0});
  CHECK(r.objective(0).name == "c1");
  CHECK(r.objective(1).name == "c2");
  CHECK(r.objective(0).type == format::ElementType::u8);
  CHECK(r.objective(1).type == format::ElementType::u16);
  CHECK(costs(r, 0) == std::vector<double>{3, 9, 4, 1, 2});
  CHECK(costs(r, 1) == std::vector<double>{10, 5, 20, 300, 0});
  const auto& m = r.metadata();
  CHECK(m.get("benchmark") == "g");
  CHECK(m.get("family") == "road");
  CHECK(m.get("id_base") == "1");
  CHECK(m.get("source.command") == "convert dimacs");
  CHECK(m.get("source.input.0.name") == "g.gr");
  CHECK(m.get("source.input.0.size") == std::to_string(std::string(kTwoCost).size()));
  CHECK(m.get("source.input.0.xxh3") == hex64(XXH3_64bits(kTwoCost, std::string(kTwoCost).size())));

  SUBCASE("the same costs in two per-objective files, with names and units") {
    write_text(dir / "a.gr", "p sp 4 5\na 1 2 3\na 2 3 4\na 1 3 9\na 3 4 1\na 4 1 2\n");
    write_text(dir / "b.gr", "p sp 4 5\na 1 2 10\na 2 3 20\na 1 3 5\na 3 4 300\na 4 1 0\n");
    auto o = gr({dir / "a.gr", dir / "b.gr"});
    o.objectives = {{"c1", ""}, {"c2", ""}};
    auto two = convert(o, dir / "two.mosb");
    CHECK(checksums(two) == checksums(r));
    CHECK(two.metadata().get("source.input.1.name") == "b.gr");
    o.objectives = {{"distance", "m"}, {"time", ""}};
    auto named = convert(o, dir / "named.mosb");
    CHECK(named.objective(0).name == "distance");
    CHECK(named.metadata().get("objective.distance.unit") == "m");
    o.objectives = {{"distance", "m"}};
    CHECK_THROWS_WITH_AS(converters::convert_dimacs(o),
                         "convert dimacs: 1 objective name given, the input has 2 cost columns",
                         Error);
  }
}

TEST_CASE("dimacs: CRLF, comments, blank lines and no final newline change nothing but metadata") {
  testing::TempDir dir;
  write_text(dir / "plain.gr", kTwoCost);
  write_text(dir / "messy.gr", kTwoCostMessy);
  auto plain = convert(gr({dir / "plain.gr"}), dir / "plain.mosb");
  auto messy = convert(gr({dir / "messy.gr"}), dir / "messy.mosb");
  CHECK(checksums(plain).size() == 7);
  CHECK(checksums(plain) == checksums(messy));
}

TEST_CASE("dimacs: gzip, bzip2, xz and zstd inputs are detected by magic bytes") {
  testing::TempDir dir;
  write_text(dir / "plain.gr", kTwoCost);
  auto plain = convert(gr({dir / "plain.gr"}), dir / "plain.mosb");
  const std::vector<std::pair<std::string, std::string>> tools = {
      {"gzip", "gzip -c"}, {"bzip2", "bzip2 -c"}, {"xz", "xz -c"}, {"zstd", "zstd -q -c"}};
  for (const auto& entry : tools) {
    const auto &tool = entry.first, &command = entry.second;  // not a binding: see pack_test.cpp
    CAPTURE(tool);
    testing::require(have_command(tool), "the '" + tool + "' command");
    // A misleading name: detection must not look at it.
    const auto packed = dir / (tool + "-input.txt");
    const std::string shell =
        command + " '" + (dir / "plain.gr").string() + "' > '" + packed.string() + "'";
    REQUIRE(std::system(shell.c_str()) == 0);
    const auto raw = slurp(packed);
    CHECK(converters::detect_compression(raw) != converters::Compression::none);
    auto r = convert(gr({packed}), dir / (tool + ".mosb"));
    CHECK(checksums(r) == checksums(plain));
    CHECK(r.metadata().get("source.input.0.size") == std::to_string(raw.size()));
    CHECK(r.metadata().get("source.input.0.xxh3") == hex64(XXH3_64bits(raw.data(), raw.size())));
  }
  write_text(dir / "broken.gz", std::string("\x1f\x8b\x08\x00garbage", 12));
  CHECK_THROWS_AS(converters::read_text_input(dir / "broken.gz"), Error);
}

TEST_CASE("dimacs: per-objective files that disagree name both files and both lines") {
  testing::TempDir dir;
  write_text(dir / "a.gr", "c first\np sp 4 3\na 1 2 1\na 2 3 1\na 3 4 1\n");
  write_text(dir / "b.gr", "p sp 4 3\na 1 2 1\nc shifted\na 2 4 1\na 3 4 1\n");
  const auto a = (dir / "a.gr").string(), b = (dir / "b.gr").string();
  CHECK_THROWS_WITH_AS(converters::convert_dimacs(gr({dir / "a.gr", dir / "b.gr"})),
                       (b + ":4:3: arc 2 4 differs from arc 2 3 at " + a +
                        ":4 (per-objective files must list the same arcs in the same order)")
                           .c_str(),
                       Error);
  write_text(dir / "c.gr", "p sp 5 3\na 1 2 1\na 2 3 1\na 3 4 1\n");
  CHECK_THROWS_WITH_AS(
      converters::convert_dimacs(gr({dir / "a.gr", dir / "c.gr"})),
      ((dir / "c.gr").string() + ":1:6: declares 5 vertices, " + a + " has 4").c_str(), Error);
}

TEST_CASE("dimacs: a header arc count that disagrees gives expected and found counts") {
  testing::TempDir dir;
  write_text(dir / "h.gr", "p sp 4 6\na 1 2 1\na 2 3 1\n");
  CHECK_THROWS_WITH_AS(
      converters::convert_dimacs(gr({dir / "h.gr"})),
      ((dir / "h.gr").string() + ":1:8: the header declares 6 arcs, found 2").c_str(), Error);
  check_parse_error("p sp 3 0\na 1 2 1\n", "t.gr:1:8: the header declares 0 arcs, found 1");
}

TEST_CASE("dimacs: malformed lines give FILE:LINE:COLUMN messages") {
  check_parse_error("a 1 2 3\np sp 3 1\n", "t.gr:1:1: arc line before the 'p sp' line");
  check_parse_error("p sp 3 1\np sp 3 1\n", "t.gr:2:1: second 'p' line (the first is line 1)");
  check_parse_error("p sp 3 1\na 1 4 7\n", "t.gr:2:5: vertex id '4' outside 1..3");
  check_parse_error("p sp 3 1\na 0 1 7\n", "t.gr:2:3: vertex id '0' outside 1..3");
  check_parse_error("p sp 3 1\na 0 3 7\n", "t.gr:2:5: vertex id '3' outside 0..2", 0);
  check_parse_error("p sp 3 1\na 1 x 7\n", "t.gr:2:5: expected a vertex id, found 'x'");
  check_parse_error("p sp 3 1\na 1 2 -7\n", "t.gr:2:7: negative cost '-7'");
  check_parse_error("p sp 3 1\na 1 2 1x\n", "t.gr:2:7: expected a cost, found '1x'");
  check_parse_error("p sp 3 1\na 1 2 inf\n", "t.gr:2:7: expected a cost, found 'inf'");
  check_parse_error("p sp 3 1\nx 1 2\n", "t.gr:2:1: unknown line type 'x'");
  check_parse_error("p sp 3 1\na 1 2\n", "t.gr:2:6: missing field: an arc line is 'a u v cost...'");
  check_parse_error("p sp 3 2\na 1 2 5\na 2 3 5 6\n",
                    "t.gr:3:9: extra field '6': expected 1 cost as on line 2");
  check_parse_error("p sp 3 2\na 1 2 5 6\na 2 3 5\n",
                    "t.gr:3:8: missing field: expected 2 costs as on line 2");
  check_parse_error("p sp 3\n", "t.gr:1:7: missing field: the header is 'p sp n m'");
  check_parse_error("p sp 3 1 9\n", "t.gr:1:10: extra field '9': the header is 'p sp n m'");
  check_parse_error("p max 3 1\n", "t.gr:1:3: expected 'sp' after 'p', found 'max'");
  check_parse_error("p sp x 1\n", "t.gr:1:6: expected the vertex count, found 'x'");
  check_parse_error("c only a comment\n", "t.gr:1:1: no 'p sp n m' line");
}

TEST_CASE("dimacs: malformed .co lines give FILE:LINE:COLUMN messages") {
  auto check_co_error = [](const std::string& text, const std::string& message) {
    CAPTURE(text);
    CHECK_THROWS_WITH_AS(converters::parse_dimacs_co(text, "t.co", 1, 2), message.c_str(), Error);
  };
  check_co_error("v 1 3 4\n", "t.co:1:1: 'v' line before the 'p aux sp co' line");
  check_co_error("p aux sp co 3\n", "t.co:1:13: declares 3 vertices, the graph has 2");
  check_co_error("p aux sp co 1\n", "t.co:1:13: declares 1 vertex, the graph has 2");
  check_co_error("p aux sp elev 2\n", "t.co:1:3: expected 'p aux sp co n'");
  check_co_error("p aux sp co\n", "t.co:1:12: missing field: the header is 'p aux sp co n'");
  check_co_error("p aux sp co 2 9\n", "t.co:1:15: extra field '9': the header is 'p aux sp co n'");
  check_co_error("p aux sp co x\n", "t.co:1:13: expected the vertex count, found 'x'");
  check_co_error("p aux sp co 4294967295\n",
                 "t.co:1:13: the vertex count '4294967295' exceeds 4294967294");
  check_co_error("p aux sp co 2\np aux sp co 2\n",
                 "t.co:2:1: second 'p' line (the first is line 1)");
  check_co_error("p aux sp co 2\nv 1 5\n",
                 "t.co:2:6: missing field: a coordinate line is 'v id x y'");
  check_co_error("p aux sp co 2\nv 1 5 6 7\n",
                 "t.co:2:9: extra field '7': a coordinate line is 'v id x y'");
  check_co_error("p aux sp co 2\nv x 5 6\n", "t.co:2:3: expected a vertex id, found 'x'");
  check_co_error("p aux sp co 2\nv 3 5 6\n", "t.co:2:3: vertex id '3' outside 1..2");
  check_co_error("p aux sp co 2\nv 1 5 6\nv 1 5 6\n", "t.co:3:3: second 'v' line for vertex 1");
  check_co_error("p aux sp co 2\nv 1 5 1.5\n",
                 "t.co:2:7: expected an integer coordinate, found '1.5'");
  check_co_error("p aux sp co 2\nv 2 5 6\n", "t.co:1:1: no 'v' line for vertex 1");
  check_co_error("c only\n", "t.co:1:1: no 'p aux sp co n' line");
  check_co_error("p aux sp co 2\nx\n", "t.co:2:1: unknown line type 'x'");
  CHECK(converters::parse_dimacs_co("p aux sp co 2\nv 2 -5 6\nv 1 7 8\n", "t.co", 1, 2) ==
        std::vector<std::int64_t>{7, 8, -5, 6});
}

TEST_CASE("dimacs: decimal columns are real-valued and --cost-type forces every column") {
  testing::TempDir dir;
  write_text(dir / "d.gr", "p sp 3 3\na 1 2 1 7\na 2 3 2.5 8\na 3 1 1e1 9\n");
  auto r = convert(gr({dir / "d.gr"}), dir / "d.mosb");
  CHECK(format::is_float(r.objective(0).type));
  CHECK(r.objective(1).type == format::ElementType::u8);
  CHECK(costs(r, 0) == std::vector<double>{1, 2.5, 10});
  auto o = gr({dir / "d.gr"});
  o.cost_type = format::ElementType::f64;
  auto forced = convert(o, dir / "f.mosb");
  CHECK(forced.objective(0).type == format::ElementType::f64);
  CHECK(forced.objective(1).type == format::ElementType::f64);
  CHECK(forced.metadata().get("source.param.cost_type") == "f64");
  o.cost_type = format::ElementType::u32;
  const auto lossy = converters::convert_dimacs(o);  // 2.5 does not fit u32: the builder refuses it
  CHECK_THROWS_AS(write_graph(lossy, dir / "x.mosb"), Error);
}

TEST_CASE("dimacs: parallel arcs, self-loops, 0-based ids and .co coordinates") {
  testing::TempDir dir;
  write_text(dir / "z.gr", "p sp 3 4\na 0 1 5\na 0 1 6\na 2 2 1\na 1 0 2\n");
  write_text(dir / "z.co",
             "c coords\np aux sp co 3\nv 0 -73530767 41085396\nv 2 1 2\nv 1 -3000000000 4\n");
  auto o = gr({dir / "z.gr"});
  o.id_base = 0;
  o.co_file = (dir / "z.co").string();
  auto r = convert(o, dir / "z.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  CHECK(r.arc_count() == 4);
  CHECK(r.metadata().get("id_base") == "0");
  CHECK(r.metadata().get("coords.scale") == "1e-6");
  CHECK(r.metadata().get("source.input.1.name") == "z.co");
  write_text(dir / "missing.co", "p aux sp co 3\nv 0 1 1\nv 2 1 1\n");
  o.co_file = (dir / "missing.co").string();
  CHECK_THROWS_WITH_AS(converters::convert_dimacs(o),
                       ((dir / "missing.co").string() + ":1:1: no 'v' line for vertex 1").c_str(),
                       Error);
  write_text(dir / "small.co", "p aux sp co 2\nv 0 1 1\nv 1 1 1\n");
  o.co_file = (dir / "small.co").string();
  CHECK_THROWS_WITH_AS(
      converters::convert_dimacs(o),
      ((dir / "small.co").string() + ":1:13: declares 2 vertices, the graph has 3").c_str(), Error);
}

TEST_CASE("dimacs: the same input in two directories gives identical bytes") {
  testing::TempDir one, two;
  std::filesystem::create_directories(two / "deeper" / "still");
  write_text(one / "g.gr", kTwoCost);
  write_text(two / "deeper" / "still" / "g.gr", kTwoCost);
  convert(gr({one / "g.gr"}), one / "out.mosb");
  convert(gr({two / "deeper" / "still" / "g.gr"}), two / "out.mosb");
  CHECK(testing::read_bytes(one / "out.mosb") == testing::read_bytes(two / "out.mosb"));
}

TEST_CASE("dimacs: real data (shared/data/dimacs-small)") {
  const auto data = testing::shared_data() / "dimacs-small";
  testing::require_shared(data / "ex1-c1.gr");
  testing::TempDir dir;
  auto r =
      convert(gr({data / "ex1-c1.gr", data / "ex1-c2.gr", data / "ex1-c3.gr"}), dir / "ex1.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  CHECK(r.vertex_count() == 5);
  CHECK(r.arc_count() == 14);
  REQUIRE(r.objective_count() == 3);
  // The first arcs of vertex 1 in the text: `a 1 2 w` then `a 1 3 w`.
  CHECK(r.forward_targets()[0] == 1);
  CHECK(r.forward_targets()[1] == 2);
  CHECK(costs(r, 0)[0] == 1);  // ex1-c1.gr: a 1 2 1
  CHECK(costs(r, 1)[0] == 2);  // ex1-c2.gr: a 1 2 2
  CHECK(r.metadata().get("benchmark") == "ex1-c1");
  CHECK(r.metadata().get("source.input.2.name") == "ex1-c3.gr");
  CHECK(r.metadata().get("source.input.0.size") == "166");
  const auto ny = (data / "USA-road-d.NY.head.gr").string();
  CHECK_THROWS_WITH_AS(converters::convert_dimacs(gr({ny})),
                       (ny + ":5:13: the header declares 733846 arcs, found 92").c_str(), Error);
}

TEST_CASE("dimacs: reading reports raw bytes over all inputs up to their total") {
  TempDir dir;
  std::string text = "p sp 3 60000\n";
  for (int i = 0; i < 60000; ++i)
    text += "a " + std::to_string(i % 3 + 1) + " " + std::to_string((i + 1) % 3 + 1) + " " +
            std::to_string(i % 97) + "\n";
  write_text(dir / "a.gr", text);
  write_text(dir / "b.gr", text);
  DimacsOptions o;
  o.gr_files = {(dir / "a.gr").string(), (dir / "b.gr").string()};
  std::uint64_t last_done = 0, last_total = 0;
  bool monotone = true, one_stage = true;
  o.progress = [&](std::string_view stage, std::uint64_t done, std::uint64_t total) {
    one_stage = one_stage && stage == "read";
    monotone = monotone && done >= last_done;
    last_done = done;
    last_total = total;
  };
  const auto g = converters::convert_dimacs(o);
  CHECK(g.tails.size() == 60000);
  CHECK(one_stage);
  CHECK(monotone);
  CHECK(last_total == 2 * text.size());
  CHECK(last_done == last_total);
}
