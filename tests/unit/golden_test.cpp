// The golden files in spec/golden are the format's memory: the writer must keep producing the
// valid file byte for byte, and every invalid file must keep failing where EXPECTED.tsv says.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>

#include "file_patch.hpp"
#include "golden_input.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {
const std::filesystem::path kGolden =
    std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "golden" / "1.0";
}

TEST_CASE("the writer reproduces the golden file byte for byte") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "small.mosb");
  const auto written = testing::read_bytes(dir / "small.mosb");
  const auto golden = testing::read_bytes(kGolden / "valid" / "small.mosb");
  REQUIRE_MESSAGE(!golden.empty(), "spec/golden/1.0/valid/small.mosb is missing");
  CHECK_MESSAGE(written == golden,
                "the writer's output changed: if deliberate, bump the format version, update "
                "spec/FORMAT.md and regenerate spec/golden with mosb_make_golden");
}

TEST_CASE("the golden file reads back with every value intact") {
  auto r = GraphReader::open(kGolden / "valid" / "small.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  CHECK(r.vertex_count() == 4);
  CHECK(r.arc_count() == 7);
  CHECK(r.objective_count() == 5);
  CHECK(r.objective(0).type == format::ElementType::u16);
  CHECK(r.objective(1).type == format::ElementType::f32);
  CHECK(r.objective(2).type == format::ElementType::f64);
  CHECK(r.objective(3).type == format::ElementType::u32);
  CHECK(r.objective(4).type == format::ElementType::u64);
  CHECK(r.metadata().get("note") == "a value with \\ backslash,\nnewline and = sign");
  CHECK(r.queries("reverse")[0] == Query{3, 0});
}

TEST_CASE("every golden invalid file fails where EXPECTED.tsv says") {
  std::ifstream list(kGolden / "invalid" / "EXPECTED.tsv");
  REQUIRE(list.good());
  std::string line;
  int cases = 0;
  while (std::getline(list, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string file, level, expected;
    std::getline(fields, file, '\t');
    std::getline(fields, level, '\t');
    std::getline(fields, expected);
    CAPTURE(file);
    ++cases;
    const auto path = kGolden / "invalid" / file;
    if (level == "open") {
      CHECK_THROWS_WITH_AS(GraphReader::open(path), doctest::Contains(expected.c_str()), Error);
      continue;
    }
    auto r = GraphReader::open(path);
    const auto at = *parse_verify_level(level);
    const auto problem = verify(r, at);
    REQUIRE(problem.has_value());
    CHECK(problem->find(expected) != std::string::npos);
    if (at == VerifyLevel::structure) CHECK_FALSE(verify(r, VerifyLevel::checksums).has_value());
  }
  CHECK(cases >= 10);
}
