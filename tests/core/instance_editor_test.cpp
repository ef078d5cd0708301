#include "mosb/instance_editor.hpp"

#include <doctest/doctest.h>

#include <map>
#include <string>

#include "file_patch.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

// A small grid instance with a second query set after `default`, so replacement order shows.
std::filesystem::path make_instance(const testing::TempDir& dir, const std::string& name) {
  converters::GridParameters p;
  p.width = 4;
  p.height = 3;
  p.objectives = 2;
  p.seed = 5;
  auto graph = converters::generate_grid(p);
  graph.queries.push_back({"extra", {{1, 2}, {3, 4}}});
  const auto path = dir / name;
  write_graph(graph, path);
  return path;
}

struct Row {
  std::string name;
  std::uint16_t kind;
  std::uint64_t checksum;
};

std::vector<Row> table(const GraphReader& r) {
  std::vector<Row> rows;
  for (const auto& s : r.sections()) rows.push_back({s.name, s.entry.kind, s.entry.checksum});
  return rows;
}

bool is_queries(const Row& row) {
  return row.kind == static_cast<std::uint16_t>(format::SectionKind::queries);
}
bool is_metadata(const Row& row) {
  return row.kind == static_cast<std::uint16_t>(format::SectionKind::metadata);
}

}  // namespace

TEST_CASE("editor: a new query set is appended, every other section unchanged") {
  testing::TempDir dir;
  const auto in = make_instance(dir, "in.mosb");
  const auto out = dir / "out.mosb";
  const auto source = GraphReader::open(in);
  Metadata metadata = source.metadata();
  metadata.set("queries.added.source", "test");
  rewrite_instance(source, metadata, {{"added", {{0, 13}, {5, 5}}}}, out);

  const auto result = GraphReader::open(out);
  const auto before = table(source), after = table(result);
  REQUIRE(after.size() == before.size() + 1);
  for (std::size_t i = 0; i < before.size(); ++i) {
    CHECK(after[i].name == before[i].name);
    CHECK(after[i].kind == before[i].kind);
    if (!is_metadata(before[i])) CHECK(after[i].checksum == before[i].checksum);
  }
  CHECK(after.back().name == "added");
  CHECK(is_queries(after.back()));
  CHECK(result.queries("added").size() == 2);
  CHECK(result.queries("added")[0] == Query{0, 13});
  CHECK(result.metadata().get("queries.added.source") == "test");
  CHECK(result.vertex_count() == source.vertex_count());
  CHECK(result.arc_count() == source.arc_count());
  CHECK_FALSE(verify(result, VerifyLevel::full));
}

TEST_CASE("editor: a replaced query set keeps its position") {
  testing::TempDir dir;
  const auto in = make_instance(dir, "in.mosb");
  const auto out = dir / "out.mosb";
  const auto source = GraphReader::open(in);
  rewrite_instance(source, source.metadata(), {{"default", {{7, 8}, {8, 7}, {0, 1}}}}, out);
  const auto result = GraphReader::open(out);
  const auto before = table(source), after = table(result);
  REQUIRE(after.size() == before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    CHECK(after[i].name == before[i].name);
    if (after[i].name == "default")
      CHECK(after[i].checksum != before[i].checksum);
    else
      CHECK(after[i].checksum == before[i].checksum);  // metadata too: it is unchanged here
  }
  CHECK(result.queries("default").size() == 3);
  CHECK(result.queries("extra").size() == 2);
  CHECK_FALSE(verify(result, VerifyLevel::full));
}

TEST_CASE("editor: rewriting the file the reader maps, and determinism") {
  testing::TempDir dir;
  const auto path = make_instance(dir, "same.mosb");
  const auto copy = make_instance(dir, "copy.mosb");
  const std::vector<QuerySet> sets = {{"extra", {{2, 3}}}, {"new", {{4, 5}}}};
  {
    const auto source = GraphReader::open(path);
    rewrite_instance(source, source.metadata(), sets, path);
    CHECK(source.queries("extra").size() == 2);  // the old mapping is still readable
  }
  {
    const auto source = GraphReader::open(copy);
    rewrite_instance(source, source.metadata(), sets, dir / "other.mosb");
  }
  const auto result = GraphReader::open(path);
  CHECK(result.queries("extra").size() == 1);
  CHECK(result.queries("new").size() == 1);
  CHECK_FALSE(verify(result, VerifyLevel::full));
  CHECK(testing::read_bytes(path) == testing::read_bytes(dir / "other.mosb"));
  // No temporary is left behind.
  std::size_t files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    files += entry.is_regular_file();
  CHECK(files == 3);
}

TEST_CASE("editor: refusals") {
  testing::TempDir dir;
  const auto in = make_instance(dir, "in.mosb");
  const auto source = GraphReader::open(in);
  const auto out = dir / "out.mosb";
  auto message = [&](const Metadata& m, const std::vector<QuerySet>& sets) -> std::string {
    try {
      rewrite_instance(source, m, sets, out);
    } catch (const Error& e) {
      return e.what();
    }
    return "(no error)";
  };
  const auto n = std::to_string(source.vertex_count());
  CHECK(message(source.metadata(), {{"q", {{0, 14}}}}) ==
        in.string() + ": query set 'q', query 0: an endpoint is not below the vertex count " + n);
  CHECK(message(source.metadata(), {{"bad name", {}}}).find("query set name 'bad name'") !=
        std::string::npos);
  CHECK(message(source.metadata(), {{"q", {}}, {"q", {}}}) ==
        in.string() + ": query set 'q' given twice");
  Metadata views = source.metadata();
  views.set("view.V.objectives", "c1");
  views.set("view.V.queries", "missing");
  CHECK(message(views, {}).find("missing") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("editor: a damaged or packed source is refused") {
  testing::TempDir dir;
  const auto in = make_instance(dir, "in.mosb");
  auto bytes = testing::read_bytes(in);
  const auto reader = GraphReader::open(in);
  const auto& targets = *reader.find(format::SectionKind::forward_targets, "forward_targets");
  bytes[targets.entry.offset] ^= std::byte{1};  // payload only: opening still succeeds
  testing::write_bytes(dir / "damaged.mosb", bytes);
  const auto damaged = GraphReader::open(dir / "damaged.mosb");
  CHECK_THROWS_WITH_AS(
      rewrite_instance(damaged, damaged.metadata(), {}, dir / "out.mosb"),
      ((dir / "damaged.mosb").string() +
       ": section 'forward_targets': checksum mismatch, the file is damaged (see mosb "
       "verify); not rewritten")
          .c_str(),
      Error);
  CHECK_FALSE(std::filesystem::exists(dir / "out.mosb"));

  // Marked as zstd (the bytes need not be a real frame: the editor refuses before reading them).
  bytes = testing::read_bytes(in);
  const auto i = testing::find_entry(bytes, "extra");
  auto e = testing::entry_of(bytes, i);
  e.encoding = static_cast<std::uint8_t>(format::Encoding::zstd);
  testing::set_entry(bytes, i, e);
  auto h = testing::header_of(bytes);
  h.required_features |= format::kFeatureZstdSections;
  testing::set_header(bytes, h);
  testing::reseal_header(bytes);
  testing::write_bytes(dir / "packed.mosb", bytes);
  const auto packed = GraphReader::open(dir / "packed.mosb");
  CHECK_THROWS_WITH_AS(
      rewrite_instance(packed, packed.metadata(), {}, dir / "out.mosb"),
      ((dir / "packed.mosb").string() +
       ": section 'extra' is packed (zstd); unpack the file before editing its query sets")
          .c_str(),
      Error);
}
