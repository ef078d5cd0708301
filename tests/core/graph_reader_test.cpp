// Hostile and damaged files: each must give a clear error at open or at the right verify level.
#include "mosb/graph_reader.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>

#include "file_patch.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/verify.hpp"
#include "temp_dir.hpp"

using namespace mosb;
using namespace mosb::testing;

namespace {

Bytes grid_bytes(const TempDir& dir) {
  write_graph(converters::generate_grid({4, 3, 2, 5}), dir / "grid.mosb");
  return read_bytes(dir / "grid.mosb");
}

std::string open_error(const Bytes& bytes) {
  try {
    GraphReader::from_memory(bytes, "f.mosb");
  } catch (const Error& e) {
    return e.what();
  }
  return "(opened)";
}

std::string verify_problem(const Bytes& bytes, VerifyLevel level) {
  auto r = GraphReader::from_memory(bytes, "f.mosb");
  return verify(r, level).value_or("(passed)");
}

// With section `section` resealed (checksums pass), the structure level reports a problem that
// starts with `start`, and the full level the same one.
void expect_rule(Bytes& b, std::size_t section, const std::string& start) {
  reseal_section(b, section);
  CHECK(verify_problem(b, VerifyLevel::checksums) == "(passed)");
  const auto problem = verify_problem(b, VerifyLevel::structure);
  CHECK_MESSAGE(problem.starts_with(start), problem);
  CHECK(verify_problem(b, VerifyLevel::full) == problem);
}

// `good` with element `index` of section `name` set to `value`: see expect_rule.
template <class T>
void expect_poked_rule(const Bytes& good, std::string_view name, std::size_t index, T value,
                       const std::string& start) {
  Bytes b = good;
  const auto section = find_entry(b, name);
  poke<T>(b, section, index, value);
  expect_rule(b, section, start);
}

}  // namespace

TEST_CASE("open refuses damaged headers and tables with a message naming the problem") {
  TempDir dir;
  const Bytes good = grid_bytes(dir);
  CHECK(open_error(good) == "(opened)");

  SUBCASE("truncated") {
    Bytes b(good.begin(), good.end() - 100);
    CHECK(open_error(b) == "f.mosb: truncated: header says " + std::to_string(good.size()) +
                               " bytes, file has " + std::to_string(b.size()));
  }
  SUBCASE("shorter than a header") {
    Bytes b(good.begin(), good.begin() + 50);
    CHECK(open_error(b).find("shorter than the 128-byte header") != std::string::npos);
  }
  SUBCASE("wrong magic") {
    Bytes b = good;
    b[1] = std::byte{'X'};
    CHECK(open_error(b) == "f.mosb: not a mosb file (wrong magic)");
  }
  SUBCASE("byte-swapped magic") {
    Bytes b = good;
    std::reverse(b.begin(), b.begin() + 8);
    CHECK(open_error(b).find("byte-swapped mosb file") != std::string::npos);
  }
  SUBCASE("byte-swapped byte-order mark") {
    Bytes b = good;
    std::reverse(b.begin() + 8, b.begin() + 12);
    CHECK(open_error(b).find("byte-swapped mosb file (byte-order mark") != std::string::npos);
  }
  SUBCASE("CRLF to LF conversion") {
    Bytes b = good;
    b.erase(b.begin() + 4);  // drops the CR of the magic's CR LF
    CHECK(open_error(b).find("text-mode transfer") != std::string::npos);
  }
  SUBCASE("newer major version") {
    Bytes b = good;
    auto h = header_of(b);
    h.version_major = 2;
    h.version_minor = 3;
    set_header(b, h);
    CHECK(open_error(b) ==
          "f.mosb: prepared with format 2.3, this reader reads format 1.x (up to 1.6)");
  }
  SUBCASE("newer minor version is read") {
    Bytes b = good;
    auto h = header_of(b);
    h.version_minor = 7;
    h.optional_features = 1ULL << 9;  // unknown optional features are ignored
    set_header(b, h);
    reseal_header(b);
    CHECK(open_error(b) == "(opened)");
  }
  SUBCASE("unknown required feature") {
    Bytes b = good;
    auto h = header_of(b);
    h.required_features = 1ULL << 5;
    set_header(b, h);
    reseal_header(b);
    CHECK(open_error(b) == "f.mosb: requires feature bit 5, unknown to this reader (format 1.6)");
  }
  SUBCASE("header checksum") {
    Bytes b = good;
    b[100] = std::byte{1};  // a reserved byte
    CHECK(open_error(b).find("header checksum mismatch") != std::string::npos);
  }
  SUBCASE("overlapping sections") {
    Bytes b = good;
    auto e = entry_of(b, 3);
    e.offset = entry_of(b, 2).offset;
    set_entry(b, 3, e);
    reseal_header(b);
    CHECK(open_error(b) == "f.mosb: sections 'forward_targets' and 'reverse_offsets' overlap");
  }
  SUBCASE("misaligned section") {
    Bytes b = good;
    auto e = entry_of(b, 2);
    e.offset += 8;
    set_entry(b, 2, e);
    reseal_header(b);
    CHECK(open_error(b).find("section 'forward_targets': offset") != std::string::npos);
    CHECK(open_error(b).find("is not 64-byte aligned") != std::string::npos);
  }
  SUBCASE("section past the data area") {
    Bytes b = good;
    auto e = entry_of(b, 6);
    e.offset = header_of(b).table_offset;
    set_entry(b, 6, e);
    reseal_header(b);
    CHECK(open_error(b).find("lie outside the data area") != std::string::npos);
  }
  SUBCASE("counts that disagree") {
    Bytes b = good;
    auto h = header_of(b);
    h.arc_count += 1;
    set_header(b, h);
    reseal_header(b);
    CHECK(open_error(b).find("section 'forward_targets': has 40 rows, but the arc count is 41") !=
          std::string::npos);
  }
  SUBCASE("objective count that disagrees") {
    Bytes b = good;
    auto h = header_of(b);
    h.objective_count = 3;
    set_header(b, h);
    reseal_header(b);
    CHECK(open_error(b) == "f.mosb: header declares 3 objectives, table has 2 cost sections");
  }
  SUBCASE("section table pointing past the end") {
    Bytes b = good;
    auto h = header_of(b);
    h.section_count += 1;
    set_header(b, h);
    CHECK(open_error(b).find("does not end at the end of the file") != std::string::npos);
  }
  SUBCASE("a row count that overflows") {
    Bytes b = good;
    auto e = entry_of(b, 6);
    e.row_count = 1ULL << 62;
    e.row_width = 1u << 20;
    set_entry(b, 6, e);
    reseal_header(b);
    CHECK(open_error(b) == "f.mosb: section 'c1': size overflows");
  }
  SUBCASE("a cost column of a signed type") {
    Bytes b = good;
    auto e = entry_of(b, 6);
    e.element_type = static_cast<std::uint8_t>(format::ElementType::i8);
    set_entry(b, 6, e);
    reseal_header(b);
    CHECK(open_error(b) == "f.mosb: section 'c1': cost type i8 is not unsigned or float");
  }
  // The kind checks of FORMAT.md §9 step 8 (SectionsByKind): each message names the section.
  auto with_kind = [&](std::string_view name, format::SectionKind kind) {
    Bytes b = good;
    const auto i = find_entry(b, name);
    auto e = entry_of(b, i);
    e.kind = static_cast<std::uint16_t>(kind);
    set_entry(b, i, e);
    reseal_header(b);
    return b;
  };
  SUBCASE("a second section of a kind held once") {
    CHECK(open_error(with_kind("reverse_sources", format::SectionKind::reverse_arcs)) ==
          "f.mosb: section 'reverse_arcs': a second reverse_arcs section");
    CHECK(open_error(with_kind("c1", format::SectionKind::metadata)) ==
          "f.mosb: section 'c1': a second metadata section");
  }
  SUBCASE("a structural section of another type") {
    Bytes b = good;
    const auto i = find_entry(b, "forward_targets");
    auto e = entry_of(b, i);
    e.element_type = static_cast<std::uint8_t>(format::ElementType::i32);
    set_entry(b, i, e);
    reseal_header(b);
    CHECK(open_error(b) == "f.mosb: section 'forward_targets': must be u32 x 1");
  }
  SUBCASE("a missing structural section") {
    Bytes b = good;
    auto e = entry_of(b, 4);
    e.kind = 99;  // now a kind this reader does not know, so it is ignored ...
    set_entry(b, 4, e);
    reseal_header(b);
    CHECK(open_error(b) ==
          "f.mosb: no reverse_sources section");  // ... and the real one is missing
  }
  SUBCASE("offsets that do not end at m") {
    Bytes b = good;
    poke<std::uint64_t>(b, 1, header_of(b).vertex_count, 7);
    reseal_section(b, 1);
    CHECK(open_error(b).find("offsets run from 0 to 7, not from 0 to the arc count 40") !=
          std::string::npos);
  }
  SUBCASE("zstd-encoded section without the feature bit") {
    Bytes b = good;
    auto e = entry_of(b, 6);
    e.encoding = 1;
    set_entry(b, 6, e);
    reseal_header(b);
    CHECK(open_error(b).find("lacks the zstd-sections feature") != std::string::npos);
  }
}

TEST_CASE("the checksums level names the damaged section, whatever its kind") {
  TempDir dir;
  const Bytes good = grid_bytes(dir);
  CHECK(verify_problem(good, VerifyLevel::full) == "(passed)");
  for (std::size_t i = 0; i < header_of(good).section_count; ++i) {
    const auto e = entry_of(good, i);
    const std::string name(format::name_of(e));
    CAPTURE(name);
    Bytes b = good;
    b[e.offset + e.stored_length / 2] ^= std::byte{0x10};
    const auto problem = verify_problem(b, VerifyLevel::checksums);
    CHECK(problem.starts_with("section '" + name + "': [checksum] mismatch"));
    CHECK(verify_problem(b, VerifyLevel::header) == "(passed)");
  }
}

TEST_CASE("the structure level names the broken rule, with checksums recomputed") {
  TempDir dir;
  const Bytes good = grid_bytes(dir);
  const auto n = header_of(good).vertex_count;
  SUBCASE("offsets decrease") {
    expect_poked_rule<std::uint64_t>(
        good, "forward_offsets", 2, 0,
        "section 'forward_offsets': [offsets-monotonic] offsets decrease at vertex 1");
  }
  SUBCASE("a target out of range") {
    expect_poked_rule<std::uint32_t>(
        good, "forward_targets", 5, static_cast<std::uint32_t>(n),
        "section 'forward_targets': [target-range] arc 5 is vertex 14");
  }
  SUBCASE("a reverse entry naming the wrong arc") {
    expect_poked_rule<std::uint32_t>(good, "reverse_arcs", 0, 7,
                                     "section 'reverse_arcs': [reverse-transpose]");
  }
  SUBCASE("a reverse entry naming the wrong source") {
    expect_poked_rule<std::uint32_t>(
        good, "reverse_sources", 0, 3,
        "section 'reverse_arcs': [reverse-transpose] entry 0 (vertex 0) says arc");
  }
  SUBCASE("a query endpoint out of range") {
    expect_poked_rule<std::uint32_t>(good, "default", 1, static_cast<std::uint32_t>(n + 3),
                                     "section 'default': [query-range] endpoint 1 is vertex 17");
  }
  SUBCASE("metadata that breaks its grammar") {
    Bytes b = good;
    const auto s = find_entry(b, "metadata");
    poke<char>(b, s, 0, 'z');  // "benchmark" -> "zenchmark": the next key is now out of order
    expect_rule(
        b, s,
        "section 'metadata': [metadata] metadata line 2: key 'family' is not in sorted order");
  }
  SUBCASE("a view naming a missing objective") {
    Bytes b = good;
    const auto s = find_entry(b, "metadata");
    const auto e = entry_of(b, s);
    std::string text(reinterpret_cast<const char*>(b.data() + e.offset), e.stored_length);
    const auto at = text.find("c1,c2");
    REQUIRE(at != std::string::npos);
    poke<char>(b, s, at + 4, '9');
    expect_rule(b, s,
                "section 'metadata': [metadata-views] metadata key 'view.Grid_2.objectives' names "
                "objective 'c9'");
  }
}

TEST_CASE("a file of megabytes: rules found across chunks, threads and transpose blocks") {
  // verify checks the forward CSR's rules with its checksums, 64 KiB at a time, and the reverse
  // CSR's rules inside the transpose's vertex blocks, on several threads (files of 1 MB and more):
  // each break must still be found, and named as in a small file, at both levels.
  TempDir dir;
  write_graph(converters::generate_grid({300, 300, 2, 5}), dir / "big.mosb");
  const Bytes good = read_bytes(dir / "big.mosb");
  REQUIRE(good.size() > (std::size_t{4} << 20));
  CHECK(verify_problem(good, VerifyLevel::full) == "(passed)");
  const auto n = header_of(good).vertex_count;
  const auto m = header_of(good).arc_count;
  auto offset_at = [&good](std::size_t index) {
    std::uint64_t v = 0;
    std::memcpy(
        &v, good.data() + entry_of(good, find_entry(good, "forward_offsets")).offset + 8 * index,
        8);
    return v;
  };
  SUBCASE("offsets decrease across the first 64 KiB chunk's end (8192 u64)") {
    expect_poked_rule<std::uint64_t>(
        good, "forward_offsets", 8192, offset_at(8191) - 1,
        "section 'forward_offsets': [offsets-monotonic] offsets decrease at vertex 8191");
  }
  SUBCASE("a target out of range at the start of a chunk (16384 u32)") {
    expect_poked_rule<std::uint32_t>(
        good, "forward_targets", 16384, static_cast<std::uint32_t>(n),
        "section 'forward_targets': [target-range] arc 16384 is vertex");
  }
  SUBCASE("reverse offsets decrease far into the file") {
    expect_poked_rule<std::uint64_t>(
        good, "reverse_offsets", 70000, 0,
        "section 'reverse_offsets': [offsets-monotonic] offsets decrease at vertex 69999");
  }
  SUBCASE("a reverse source out of range in a late block") {
    expect_poked_rule<std::uint32_t>(
        good, "reverse_sources", m - 3, static_cast<std::uint32_t>(n + 1),
        "section 'reverse_sources': [source-range] entry " + std::to_string(m - 3) + " is vertex " +
            std::to_string(n + 1));
  }
  SUBCASE("a reverse entry naming the wrong arc in a middle block") {
    expect_poked_rule<std::uint32_t>(
        good, "reverse_arcs", m / 2, 0,
        "section 'reverse_arcs': [reverse-transpose] entry " + std::to_string(m / 2));
  }
  SUBCASE("a later rule is reported after an earlier one, whichever thread finds it first") {
    Bytes b = good;
    const auto arcs = find_entry(b, "reverse_arcs");
    poke<std::uint32_t>(b, arcs, 5, 0);
    reseal_section(b, arcs);
    const auto s = find_entry(b, "forward_targets");
    poke<std::uint32_t>(b, s, m - 1, static_cast<std::uint32_t>(n));
    expect_rule(b, s, "section 'forward_targets': [target-range] arc " + std::to_string(m - 1));
  }
}

TEST_CASE("float cost columns must be finite and non-negative") {
  TempDir dir;
  GraphInput g;
  g.vertex_count = 2;
  g.tails = {0, 1};
  g.heads = {1, 0};
  g.costs.push_back({"w", "", std::vector<double>{0.1, 0.2}, {}});
  write_graph(g, dir / "f.mosb");
  const Bytes good = read_bytes(dir / "f.mosb");
  const auto s = find_entry(good, "w");
  Bytes b = good;
  poke<double>(b, s, 1, std::nan(""));
  reseal_section(b, s);
  CHECK(verify_problem(b, VerifyLevel::structure).starts_with("section 'w': [cost-finite] arc 1"));
  b = good;
  poke<double>(b, s, 0, -2.0);
  reseal_section(b, s);
  CHECK(verify_problem(b, VerifyLevel::structure)
            .starts_with("section 'w': [cost-nonnegative] arc 0"));
}

TEST_CASE("packed sections are refused for zero-copy access") {
  TempDir dir;
  Bytes b = grid_bytes(dir);
  auto h = header_of(b);
  h.required_features = format::kFeatureZstdSections;
  set_header(b, h);
  auto e = entry_of(b, 6);
  e.encoding = 1;
  set_entry(b, 6, e);
  reseal_header(b);
  auto r = GraphReader::from_memory(b, "f.mosb");
  CHECK_THROWS_WITH_AS(
      (void)r.cost<std::uint8_t>(0),
      doctest::Contains("section 'c1' is zstd-packed and cannot be mapped zero-copy"), Error);
  CHECK(r.forward_targets().size() == 40);
}

TEST_CASE("opening a path that is not a mosb file") {
  TempDir dir;
  CHECK_THROWS_WITH_AS(GraphReader::open(dir / "missing.mosb"),
                       doctest::Contains("missing.mosb: cannot open"), Error);
  CHECK_THROWS_WITH_AS(GraphReader::open(dir.path()), doctest::Contains("not a regular file"),
                       Error);
  write_bytes(dir / "empty.mosb", {});
  CHECK_THROWS_WITH_AS(
      GraphReader::open(dir / "empty.mosb"),
      doctest::Contains("empty.mosb: not a mosb file: 0 bytes is shorter than the 128-byte header"),
      Error);
}

TEST_CASE("open with a verify level refuses a damaged payload that plain open accepts") {
  TempDir dir;
  Bytes b = grid_bytes(dir);
  const auto s = find_entry(b, "c1");
  const auto e = entry_of(b, s);
  b[e.offset + 3] ^= std::byte{0x10};
  write_bytes(dir / "d.mosb", b);
  CHECK_NOTHROW(GraphReader::open(dir / "d.mosb"));
  CHECK(GraphReader::open(dir / "d.mosb").verified_level() == VerifyLevel::header);
  CHECK_NOTHROW(
      GraphReader::open(dir / "d.mosb", VerifyLevel::structure));  // costs are u8: any value fits
  CHECK_THROWS_WITH_AS(
      GraphReader::open(dir / "d.mosb", VerifyLevel::full),
      doctest::Contains("d.mosb: file is damaged: section 'c1': [checksum] mismatch"), Error);
  CHECK_THROWS_WITH_AS(GraphReader::open(dir / "d.mosb", VerifyLevel::checksums),
                       doctest::Contains("; run mosb verify"), Error);
  CHECK(GraphReader::open(dir / "grid.mosb", VerifyLevel::full).verified_level() ==
        VerifyLevel::full);
  CHECK(covers(VerifyLevel::full, VerifyLevel::structure));
  CHECK_FALSE(covers(VerifyLevel::structure, VerifyLevel::checksums));
  CHECK_FALSE(covers(VerifyLevel::header, VerifyLevel::full));
}

TEST_CASE("the structure level refuses non-zero bytes in alignment padding") {
  TempDir dir;
  const Bytes good = grid_bytes(dir);
  // The first gap after a section whose length is not a multiple of 64.
  std::size_t gap = 0;
  for (std::size_t i = 0; i < header_of(good).section_count && gap == 0; ++i) {
    const auto e = entry_of(good, i);
    if (e.stored_length % 64 != 0) gap = e.offset + e.stored_length;
  }
  REQUIRE(gap != 0);
  Bytes b = good;
  b[gap] = std::byte{0x5A};
  CHECK(verify_problem(b, VerifyLevel::checksums) == "(passed)");  // no checksum covers padding
  const auto problem = verify_problem(b, VerifyLevel::structure);
  CHECK_MESSAGE(problem.starts_with("[padding] byte " + std::to_string(gap) + " (before section '"),
                problem);
  CHECK(problem.find("is 0x5a") != std::string::npos);
  CHECK(verify_problem(b, VerifyLevel::full) == problem);
  b = good;
  b[header_of(good).table_offset - 1] = std::byte{1};  // the gap before the table
  CHECK(verify_problem(b, VerifyLevel::structure).find("before the section table") !=
        std::string::npos);
  CHECK(verify_problem(good, VerifyLevel::full) == "(passed)");
}

TEST_CASE("the structure level checks metadata keys with a defined value set") {
  TempDir dir;
  auto problem_with = [&](const std::string& key, const std::string& value) {
    auto g = converters::generate_grid({4, 3, 2, 5});
    g.metadata.set(key, value);
    write_graph(g, dir / "m.mosb");
    const auto r = GraphReader::open(dir / "m.mosb");
    CHECK(verify(r, VerifyLevel::checksums) == std::nullopt);
    return verify(r, VerifyLevel::structure).value_or("(passed)");
  };
  CHECK(problem_with("id_base", "7") ==
        "section 'metadata': [metadata-values] metadata key 'id_base' is '7', not one of 0, 1");
  CHECK(problem_with("id_base", "1") == "(passed)");
  CHECK(problem_with("family", "rood").find("'family' is 'rood', not one of road, synthetic") !=
        std::string::npos);
  CHECK(problem_with("queries.a.b.id_base", "2").find("'queries.a.b.id_base' is '2'") !=
        std::string::npos);
  CHECK(problem_with("queries.q.allow_same", "yes").find("not one of 0, 1") != std::string::npos);
  CHECK(problem_with("family", "\x1b[2Jx").find("is '\\x1b[2Jx'") != std::string::npos);
  CHECK(problem_with("queries.q.seed", "anything") == "(passed)");
}

namespace {
// The grid file with `extra` more empty sections of `kind` named x0, x1, ... appended to its table;
// the last one repeats the name of the first when `duplicate_last`.
Bytes with_many_sections(const Bytes& good, std::size_t extra, std::uint16_t kind,
                         bool duplicate_last) {
  const auto h = header_of(good);
  Bytes b(good.begin(), good.end());
  b.resize(b.size() + extra * sizeof(format::SectionEntry));
  for (std::size_t i = 0; i < extra; ++i) {
    format::SectionEntry e{};
    const std::string name = "x" + std::to_string(duplicate_last && i + 1 == extra ? 0 : i);
    std::memcpy(e.name.data(), name.data(), name.size());
    e.kind = kind;
    e.element_type = static_cast<std::uint8_t>(format::ElementType::u32);
    e.row_width = 2;
    e.offset = format::kHeaderSize;
    e.checksum = XXH3_64bits(nullptr, 0);
    std::memcpy(b.data() + h.table_offset + (h.section_count + i) * sizeof e, &e, sizeof e);
  }
  auto nh = h;
  nh.section_count = static_cast<std::uint32_t>(h.section_count + extra);
  nh.file_size = b.size();
  set_header(b, nh);
  reseal_header(b);
  return b;
}
}  // namespace

TEST_CASE("section names are unique within a kind, known or not, checked in linear time") {
  TempDir dir;
  const Bytes good = grid_bytes(dir);
  const auto queries = static_cast<std::uint16_t>(format::SectionKind::queries);
  // 10^6 empty query sets: a pairwise check would make 5*10^11 comparisons.
  const Bytes many = with_many_sections(good, 1'000'000, queries, false);
  const auto start = std::chrono::steady_clock::now();
  CHECK(open_error(many) == "(opened)");
  CHECK(open_error(with_many_sections(good, 1'000'000, queries, true)) ==
        "f.mosb: section 'x0': a second queries section of that name");
  MESSAGE("opening two files of 10^6 sections took "
          << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()
          << " s");
  // A kind this reader does not know is held to the same rule.
  CHECK(open_error(with_many_sections(good, 3, 200, true)) ==
        "f.mosb: section 'x0': a second kind 200 section of that name");
  CHECK(open_error(with_many_sections(good, 3, 200, false)) == "(opened)");
  // The same name in two kinds is allowed.
  Bytes two_kinds = with_many_sections(good, 1, 200, false);
  two_kinds = with_many_sections(two_kinds, 1, queries, false);
  CHECK(open_error(two_kinds) == "(opened)");
}
