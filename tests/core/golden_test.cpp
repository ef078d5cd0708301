// The golden files in spec/golden are the format's memory: the writer must keep producing the
// valid file byte for byte, and every invalid file must keep failing where EXPECTED.tsv says.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>

#include "file_patch.hpp"
#include "golden_input.hpp"
#include "golden_references.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;

namespace {
const std::filesystem::path kGolden =
    std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "golden" / "1.0";
const std::filesystem::path kGoldenReferences =
    std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "golden" / "1.1" / "references";

// Every file listed in DIR/invalid/EXPECTED.tsv fails at its level with its message; returns the
// number of files.
int check_invalid_files(const std::filesystem::path& golden) {
  int cases = 0;
  for (const auto& row : testing::expected_rows(golden / "invalid" / "EXPECTED.tsv")) {
    REQUIRE(row.size() == 3);
    const auto &file = row[0], &level = row[1], &expected = row[2];
    CAPTURE(file);
    ++cases;
    const auto path = golden / "invalid" / file;
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
  return cases;
}
}  // namespace

TEST_CASE("the writer reproduces the golden file byte for byte") {
  testing::TempDir dir;
  write_graph(testing::golden_input(), dir / "small.mosb");
  const auto written = testing::read_bytes(dir / "small.mosb");
  const auto golden = testing::read_bytes(kGolden / "valid" / "small.mosb");
  REQUIRE_MESSAGE(!golden.empty(), "spec/golden/1.0/valid/small.mosb is missing");
  CHECK_MESSAGE(written == golden,
                "the writer's output changed: if deliberate, bump the format version, update "
                "spec/FORMAT.md and regenerate spec/golden with mosb_make_golden instance");
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
  CHECK(check_invalid_files(kGolden) >= 10);
}

TEST_CASE("golden query references: reproduced byte for byte, read back, faults caught") {
  testing::TempDir dir;
  write_graph(testing::golden_references_input(), dir / "references.mosb");
  const auto golden = testing::read_bytes(kGoldenReferences / "valid" / "references.mosb");
  REQUIRE_MESSAGE(!golden.empty(), "spec/golden/1.1/references/valid/references.mosb is missing");
  CHECK_MESSAGE(testing::read_bytes(dir / "references.mosb") == golden,
                "the writer no longer reproduces the golden references file: regenerate it with "
                "mosb_make_golden references only with a version change in spec/FORMAT.md");
  const auto r = GraphReader::open(kGoldenReferences / "valid" / "references.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  CHECK(r.header().version_minor == 0);
  REQUIRE(r.query_reference("default").has_value());
  CHECK((*r.query_reference("default"))[0] == 2.5);
  CHECK(check_invalid_files(kGoldenReferences) == 6);
}
