#include "mosb/converters/query_import.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "mosb/error.hpp"
#include "requirements.hpp"
#include "test_files.hpp"

using mosb::Query;
using mosb::converters::parse_query_file;
using mosb::converters::QueryFileOptions;

namespace {

using namespace mosb::testing;  // slurp

QueryFileOptions options(unsigned id_base, std::uint64_t n, const char* match = nullptr) {
  QueryFileOptions o;
  o.id_base = id_base;
  o.vertex_count = n;
  if (match) o.match = match;
  return o;
}

std::vector<Query> parse(const std::string& text, const QueryFileOptions& o) {
  return parse_query_file(text, "q.txt", o);
}

std::string error_of(const std::string& text, const QueryFileOptions& o) {
  try {
    parse(text, o);
  } catch (const mosb::Error& e) {
    return e.what();
  }
  return "(no error)";
}

const std::vector<Query> kThree = {{0, 1}, {2, 3}, {4, 0}};

}  // namespace

TEST_CASE("query files: every separator gives the same pairs") {
  const auto o = options(1, 5);
  CHECK(parse("1 2\n3 4\n5 1\n", o) == kThree);
  CHECK(parse("1\t2\n3   4\n  5 1  \n", o) == kThree);
  CHECK(parse("1,2\n3 ,4\n5 , 1\n", o) == kThree);
  CHECK(parse("1, 2\n3 ,  4\n5,1\n", o) == kThree);
  CHECK(parse("1;2\n3 ; 4\n5;1\n", o) == kThree);
  CHECK(parse("g.gr 1 2\n g.gr 3 4\ng.gr\t5 1\n", o) == kThree);
}

TEST_CASE("query files: comments, blank lines, CRLF, no final newline, byte-order mark") {
  const auto o = options(0, 5);
  const std::vector<Query> expected = {{0, 1}, {2, 3}, {4, 0}};
  CHECK(parse("# pairs\r\n\r\nc dimacs comment\r\nc\r\n0, 1\r\n  \t\r\n# x\r\n2 , 3\r\n4,0", o) ==
        expected);
  CHECK(parse("\xEF\xBB\xBF"
              "0 1\n2 3\n4 0\n",
              o) == expected);
  CHECK(parse("0 1\n#2 3\n2 3\n4 0\n\n\n", o) == expected);
}

TEST_CASE("query files: id base and range") {
  CHECK(parse("0 4\n", options(0, 5)) == std::vector<Query>{{0, 4}});
  CHECK(parse("1 5\n", options(1, 5)) == std::vector<Query>{{0, 4}});
  CHECK(error_of("1 2\n3 5\n", options(0, 5)) == "q.txt:2:3: vertex id '5' outside 0..4");
  CHECK(error_of("1 2\n\n0 , 3\n", options(1, 5)) == "q.txt:3:1: vertex id '0' outside 1..5");
  CHECK(error_of("1 99999999999999999999999\n", options(1, 5)) ==
        "q.txt:1:3: vertex id '99999999999999999999999' outside 1..5");
  CHECK(error_of("g 1 2\n", options(0, 0)) ==
        "q.txt:1:3: vertex id '1' outside (none: the graph has no vertices)");
}

TEST_CASE("query files: malformed lines name line and column") {
  const auto o = options(0, 10);
  CHECK(error_of("1 2\n3\n", o) == "q.txt:2:2: missing field: expected 'start goal'");
  CHECK(error_of("1,\n", o) ==
        "q.txt:1:3: missing field: expected 'start goal' or 'graph start goal'");
  CHECK(error_of("1,,2\n", o) == "q.txt:1:3: unexpected ','");
  CHECK(error_of(", 1 2\n", o) == "q.txt:1:1: unexpected ','");
  CHECK(error_of("1 2 3\n", o) ==
        "q.txt:1:5: extra field '3': expected 'start goal' or 'graph start goal'");
  CHECK(error_of("1, 2, 3\n", o) ==
        "q.txt:1:5: extra field ',': expected 'start goal' or 'graph start goal'");
  CHECK(error_of("1 x\n", o) == "q.txt:1:3: expected a vertex id, found 'x'");
  CHECK(error_of("1 -2\n", o) == "q.txt:1:3: expected a vertex id, found '-2'");
  CHECK(error_of("1 2\ng 1 2\n", o) ==
        "q.txt:2:1: a 'graph start goal' line, but line 1 is 'start goal'");
  CHECK(error_of("g 1 2\n1 2\n", o) ==
        "q.txt:2:1: a 'start goal' line, but line 1 is 'graph start goal'");
  CHECK(error_of("g 1 2\ng 1 2 3\n", o) ==
        "q.txt:2:7: extra field '3': expected 'graph start goal'");
  CHECK(error_of("", o) == "q.txt: no queries");
  CHECK(error_of("# only a comment\r\n", o) == "q.txt: no queries");
}

TEST_CASE("query files: graph fields and --match") {
  const std::string text = "/a/x_1.gr 1 2\n/a/y_2.gr 3 4\n/a/x_1.gr 5 6\n";
  CHECK(parse(text, options(0, 10, "x_1")) == std::vector<Query>{{1, 2}, {5, 6}});
  CHECK(parse(text, options(0, 10, "y_")) == std::vector<Query>{{3, 4}});
  CHECK(error_of(text, options(0, 10)) ==
        "q.txt:2:1: the file names more than one graph ('/a/x_1.gr' on line 1, '/a/y_2.gr' here): "
        "choose one with match TEXT");
  CHECK(error_of(text, options(0, 10, ".gr")) ==
        "q.txt:2:1: match '.gr' selects more than one graph ('/a/x_1.gr' on line 1, '/a/y_2.gr' "
        "here)");
  CHECK(error_of(text, options(0, 10, "zzz")) == "q.txt: no line's graph field contains 'zzz'");
  CHECK(error_of("1 2\n", options(0, 10, "x")) ==
        "q.txt:1:1: match 'x' given, but the lines have no graph field");
  // Unselected lines are not range-checked: their ids belong to another graph.
  CHECK(parse("big.gr 100 200\nsmall.gr 1 2\n", options(0, 3, "small")) ==
        std::vector<Query>{{1, 2}});
}

TEST_CASE("query files: the real DIMACS and targeted-MOSP query files") {
  const auto data = mosb::testing::shared_data();
  const auto ny = data / "dimacs-queries" / "USA-road-NY-queries";
  const auto bay = data / "dimacs-queries" / "USA-road-BAY-queries";
  const auto inst = data / "netmaker" / "netMaker_4d.inst";
  for (const auto& path : {ny, bay, inst}) mosb::testing::require_shared(path);
  // USA-road-d.NY has 264346 vertices, BAY 321270; ids are 1-based.
  const auto ny_pairs = parse_query_file(slurp(ny), ny.string(), options(1, 264346));
  REQUIRE(ny_pairs.size() == 1000);
  CHECK(ny_pairs[0] == Query{9898, 7856});
  const auto bay_pairs = parse_query_file(slurp(bay), bay.string(), options(1, 321270));
  REQUIRE(bay_pairs.size() == 100);
  CHECK(bay_pairs[0] == Query{401, 181062});

  const auto inst_text = slurp(inst);
  const auto nm = parse_query_file(inst_text, inst.string(), options(0, 10000, "_79134.gr"));
  REQUIRE(nm.size() == 40);
  CHECK(nm[0] == Query{8326, 5528});
  const auto without_match = error_of(inst_text, options(0, 10000));
  CHECK(without_match.find(":21:1: the file names more than one graph ('...") != std::string::npos);
  CHECK(without_match.find("_79134.gr' on line 1, '...") != std::string::npos);
  CHECK(without_match.find("_442970.gr' here): choose one with match TEXT") != std::string::npos);
}
