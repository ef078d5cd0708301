// Solution files (spec/SOLUTIONS.md): the writer's checks, the reader's view of what was written,
// the binding to the instance, and the golden files in spec/golden/1.3/solutions (and the older
// layout's in 1.1/solutions, which stay readable).
#include "mosb/solution_file.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "file_patch.hpp"
#include "golden_input.hpp"
#include "golden_solutions.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/pack.hpp"
#include "mosb/solution_merge.hpp"
#include "mosb/solution_verify.hpp"
#include "packed_faults.hpp"
#include "solution_faults.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;

namespace {
const std::filesystem::path kGolden = std::filesystem::path(MOSB_SOURCE_DIR) / "spec" / "golden";
const auto kSmall = kGolden / "1.0" / "valid" / "small.mosb";
const auto kSolutions = kGolden / "1.3" / "solutions";
// Written before path sums (front_cost in the arc type): read, never regenerated.
const auto kOldSolutions = kGolden / "1.1" / "solutions";
}  // namespace

TEST_CASE("the solution writer reproduces the golden solution file byte for byte") {
  testing::TempDir dir;
  testing::write_golden_solutions(GraphReader::open(kSmall), dir / "small.sol.mosb");
  const auto written = testing::read_bytes(dir / "small.sol.mosb");
  const auto golden = testing::read_bytes(kSolutions / "valid" / "small.sol.mosb");
  REQUIRE_MESSAGE(!golden.empty(), "spec/golden/1.3/solutions/valid/small.sol.mosb is missing");
  CHECK_MESSAGE(written == golden,
                "the solution writer's output changed: if deliberate, update spec/SOLUTIONS.md "
                "and regenerate with mosb_make_golden solutions");
}

TEST_CASE("the golden solution file reads back with every value intact") {
  const auto instance = GraphReader::open(kSmall);
  const auto r = SolutionReader::open(kSolutions / "valid" / "small.sol.mosb", instance);
  CHECK_FALSE(r.verify_payload().has_value());
  CHECK(r.header().file_kind == 2);
  CHECK(r.header().version_minor == 3);
  CHECK(r.stores_path_sums());
  CHECK(r.header().vertex_count == 4);
  CHECK(r.instance_digest() == instance.digest());
  CHECK(r.view_name() == "Small_2");
  CHECK(r.query_set() == "default");
  REQUIRE(r.objective_count() == 2);
  CHECK(r.objective_name(0) == "distance");
  CHECK(r.objective_type(0) == format::ElementType::u64);  // sums of u16 arc costs
  CHECK(r.objective_name(1) == "time");
  CHECK(r.objective_type(1) == format::ElementType::f64);  // sums of f32 arc costs
  REQUIRE(r.query_count() == 3);
  CHECK(r.vector_count() == 3);
  CHECK(r.status(0) == QueryStatus::solved);
  CHECK(r.status(2) == QueryStatus::timeout);
  CHECK(r.front_size(0) == 2);
  CHECK(r.front_size(2) == 0);
  const auto distance = r.front<std::uint64_t>(0, 0);
  CHECK(std::vector<std::uint64_t>(distance.begin(), distance.end()) ==
        std::vector<std::uint64_t>{60, 80});
  CHECK(r.front<double>(1, 1)[0] == 7.5);
  CHECK(r.value_as_double(1, 1) == 3.75);
  CHECK_THROWS_AS(r.column<std::uint32_t>(0), Error);
  const auto sum = r.visit_column(0, [](auto column) {
    double total = 0;
    for (auto v : column) total += static_cast<double>(v);
    return total;
  });
  CHECK(sum == 260);
  CHECK(r.runtime_seconds(0) == 0.5);
  CHECK_FALSE(r.runtime_seconds(2).has_value());
  CHECK(r.count_statistic(Statistic::expanded, 1) == 5u);
  CHECK_FALSE(r.count_statistic(Statistic::peak_memory_bytes, 1).has_value());
  REQUIRE(r.has_paths());
  const auto path = r.path(1);
  CHECK(std::vector<std::uint32_t>(path.begin(), path.end()) ==
        std::vector<std::uint32_t>{0, 1, 2, 3});
  const auto solver = r.solver();
  CHECK(solver.name == "hand");
  CHECK(solver.epsilon == "0");
  CHECK(solver.parameters.at("order") == "lexicographic");
}

TEST_CASE("a solution file of the older layout (1.1, arc-type columns) reads widened") {
  const auto instance = GraphReader::open(kSmall);
  const auto r = SolutionReader::open(kOldSolutions / "valid" / "small.sol.mosb", instance);
  CHECK(r.header().version_minor == 1);
  CHECK_FALSE(r.stores_path_sums());
  CHECK_FALSE(r.verify_payload().has_value());
  CHECK(r.objective_type(0) == format::ElementType::u16);
  CHECK(r.objective_type(1) == format::ElementType::f32);
  const auto current = SolutionReader::open(kSolutions / "valid" / "small.sol.mosb", instance);
  REQUIRE(r.vector_count() == current.vector_count());
  for (std::size_t i = 0; i < 2; ++i)
    for (std::uint64_t row = 0; row < r.vector_count(); ++row)
      CHECK(r.value_as_double(i, row) == current.value_as_double(i, row));
  CHECK(r.visit_column(0, [](auto column) { return static_cast<double>(column[1]); }) == 80);
}

TEST_CASE("path sums beyond the arc type are stored as u64 (a u16 objective summing to 70000)") {
  testing::TempDir dir;
  const auto instance = GraphReader::open(kSmall);
  SolutionWriter w(instance, "Small_2");
  w.set_query(0, QueryStatus::solved, std::vector<double>{70000, 0.1, 4294967296.0 * 3, 0.05});
  w.set_query(1, QueryStatus::solved, std::vector<double>{9007199254740992.0, 1});  // 2^53
  w.write(dir / "s.sol.mosb");
  const auto r = SolutionReader::open(dir / "s.sol.mosb", instance);
  CHECK_FALSE(r.verify_payload().has_value());
  CHECK(r.column<std::uint64_t>(0)[0] == 70000u);
  CHECK(r.column<std::uint64_t>(0)[1] == 3 * (std::uint64_t{1} << 32));
  CHECK(r.column<std::uint64_t>(0)[2] == std::uint64_t{1} << 53);
  CHECK(r.column<double>(1)[0] == 0.1);  // an f64 sum, not rounded to f32
}

TEST_CASE("failed queries carry no front and only an exit status") {
  testing::TempDir dir;
  const auto instance = GraphReader::open(kSmall);
  SolutionWriter w(instance, "Small_2");
  QueryStatistics crashed;
  crashed.exit_status = 139;  // SIGSEGV: 128 + 11
  w.set_query(0, QueryStatus::failed, {}, crashed);
  w.set_query(1, QueryStatus::failed, {});
  CHECK_THROWS_WITH(w.set_query(2, QueryStatus::failed, std::vector<double>{1, 2}),
                    doctest::Contains("failed with a front"));
  CHECK_THROWS_WITH(w.set_query(2, QueryStatus::failed, {}, {1.0, {}, {}, {}}),
                    doctest::Contains("failed carries no statistics"));
  CHECK_THROWS_WITH(w.set_query(2, QueryStatus::solved, std::vector<double>{1, 2}, crashed),
                    doctest::Contains("solved carries no exit_status"));
  w.write(dir / "s.sol.mosb");
  const auto r = SolutionReader::open(dir / "s.sol.mosb", instance);
  CHECK_FALSE(r.verify_payload().has_value());
  CHECK(r.status(0) == QueryStatus::failed);
  CHECK(r.count_statistic(Statistic::exit_status, 0) == 139u);
  CHECK_FALSE(r.count_statistic(Statistic::exit_status, 1).has_value());
  CHECK(parse_query_status("failed") == QueryStatus::failed);
  CHECK(to_string(QueryStatus::failed) == "failed");
}

TEST_CASE("a solution file opened against another instance names both digests") {
  testing::TempDir dir;
  auto input = testing::golden_input();
  input.costs[0].values = std::vector<std::uint64_t>{41, 10, 30, 20, 50, 5, 300};
  write_graph(input, dir / "other.mosb");
  const auto other = GraphReader::open(dir / "other.mosb");
  const auto small = GraphReader::open(kSmall);
  try {
    (void)SolutionReader::open(kSolutions / "valid" / "small.sol.mosb", other);
    FAIL("opened against the wrong instance");
  } catch (const Error& e) {
    const std::string message = e.what();
    CHECK(e.code() == ErrorCode::invalid_argument);
    CHECK(message.find(small.digest()) != std::string::npos);
    CHECK(message.find(other.digest()) != std::string::npos);
  }
}

TEST_CASE("an instance is not a solution file and a solution file is not an instance") {
  CHECK_THROWS_WITH_AS(SolutionReader::open(kSmall), doctest::Contains("file kind 1"), Error);
  CHECK_THROWS_WITH_AS(GraphReader::open(kSolutions / "valid" / "small.sol.mosb"),
                       doctest::Contains("file kind 2"), Error);
}

TEST_CASE("the solution writer refuses what the instance's cost types cannot hold") {
  const auto instance = GraphReader::open(kSmall);
  SolutionWriter w(instance, "Small_2");
  CHECK(w.query_count() == 3);
  CHECK_THROWS_WITH(w.set_query(0, QueryStatus::solved, std::vector<double>{60.5, 1}),
                    doctest::Contains("vector 0, objective 'distance': cost is not an integer"));
  CHECK_THROWS_WITH(
      w.set_query(0, QueryStatus::solved, std::vector<double>{1, 1, 9007199254740994.0, 1}),
      doctest::Contains("vector 1, objective 'distance': path sum above 2^53"));
  CHECK_THROWS_WITH(w.set_query(0, QueryStatus::solved, std::vector<double>{1, -1}),
                    doctest::Contains("negative"));
  CHECK_THROWS_WITH(w.set_query(0, QueryStatus::solved, std::vector<double>{1, 2, 3}),
                    doctest::Contains("not a whole number"));
  CHECK_THROWS_WITH(w.set_query(3, QueryStatus::solved, std::vector<double>{1, 2}),
                    doctest::Contains("is not in query set 'default'"));
  CHECK_THROWS_WITH(w.set_query(1, QueryStatus::timeout, std::vector<double>{1, 2}),
                    doctest::Contains("only solved queries"));
  CHECK_THROWS_WITH(w.set_query(1, QueryStatus::timeout, {}, {1.0, {}, {}, {}}),
                    doctest::Contains("carries no statistics"));
  CHECK_THROWS_WITH(w.set_query(1, QueryStatus::solved, {}), doctest::Contains("empty front"));
}

TEST_CASE("queries never set are written as not-run, and the file binds to the view") {
  testing::TempDir dir;
  const auto instance = GraphReader::open(kSmall);
  SolutionWriter w(instance, "Small_2");
  w.set_query(1, QueryStatus::disconnected, {}, {2.0, 10, 12, 4096});
  w.write(dir / "s.sol.mosb");
  const auto r = SolutionReader::open(dir / "s.sol.mosb", instance);
  CHECK_FALSE(r.verify_payload().has_value());
  CHECK(r.status(0) == QueryStatus::not_run);
  CHECK(r.status(1) == QueryStatus::disconnected);
  CHECK(r.vector_count() == 0);
  CHECK_FALSE(r.has_paths());
  CHECK(r.statistics(1).peak_memory_bytes == 4096u);
  CHECK(parse_query_status("memory-limit") == QueryStatus::memory_limit);
  CHECK(to_string(QueryStatus::not_run) == "not-run");
}

TEST_CASE("every golden invalid solution file fails where EXPECTED.tsv says") {
  // The older layout's invalid files must keep failing where they did.
  for (const auto& row : testing::expected_rows(kOldSolutions / "invalid" / "EXPECTED.tsv")) {
    REQUIRE(row.size() == 3);
    CAPTURE(row[0]);
    const auto path = kOldSolutions / "invalid" / row[0];
    if (row[1] == "open") {
      CHECK_THROWS_WITH_AS(SolutionReader::open(path), doctest::Contains(row[2].c_str()), Error);
      continue;
    }
    const auto problem = SolutionReader::open(path).verify_payload();
    REQUIRE(problem.has_value());
    CHECK_MESSAGE(problem->find(row[2]) != std::string::npos, *problem);
  }
  int cases = 0;
  for (const auto& row : testing::expected_rows(kSolutions / "invalid" / "EXPECTED.tsv")) {
    REQUIRE(row.size() == 3);
    const auto &file = row[0], &stage = row[1], &expected = row[2];
    CAPTURE(file);
    ++cases;
    const auto path = kSolutions / "invalid" / file;
    if (stage == "open") {
      CHECK_THROWS_WITH_AS(SolutionReader::open(path), doctest::Contains(expected.c_str()), Error);
      continue;
    }
    const auto r = SolutionReader::open(path);
    const auto problem = r.verify_payload();
    REQUIRE(problem.has_value());
    CHECK_MESSAGE(problem->find(expected) != std::string::npos, *problem);
  }
  CHECK(cases == static_cast<int>(std::size(testing::kSolutionFaults)));
}

namespace {
// A chain 0 -> 1 -> 2 -> 3 of u16 arcs costing 60000 each (paths sum past 65535), and 4 -> 0: 4
// reaches everything, nothing reaches 4, 3 reaches nothing.
std::filesystem::path write_chain(const std::filesystem::path& dir) {
  GraphInput g;
  g.vertex_count = 5;
  g.tails = {0, 1, 2, 4};
  g.heads = {1, 2, 3, 0};
  g.costs.push_back(
      {"c", "", std::vector<std::uint64_t>{60000, 60000, 60000, 7}, format::ElementType::u16});
  g.queries.push_back({"q", {{0, 3}, {0, 4}, {3, 0}, {4, 3}}});
  g.metadata.set("view.V.objectives", "c");
  g.metadata.set("view.V.queries", "q");
  write_graph(g, dir / "chain.mosb");
  return dir / "chain.mosb";
}
}  // namespace

TEST_CASE("verify sums a path's u16 arcs exactly in u64 and compares with the stored sum") {
  testing::TempDir dir;
  const auto instance = GraphReader::open(write_chain(dir.path()), VerifyLevel::full);
  const std::vector<std::vector<std::uint32_t>> path = {{0, 1, 2, 3}};
  for (const double stored : {180000.0, 180001.0}) {
    SolutionWriter w(instance, "V");
    w.set_query(0, QueryStatus::solved, std::vector<double>{stored}, {}, path);
    w.write(dir / "s.sol.mosb");
    const auto problem = verify_solutions(SolutionReader::open(dir / "s.sol.mosb"), instance);
    if (stored == 180000.0) {
      CHECK_FALSE(problem.has_value());
    } else {
      REQUIRE(problem.has_value());
      CHECK(problem->find("[path-cost] the arcs sum to (180000), not to the stored vector") !=
            std::string::npos);
    }
  }
}

TEST_CASE("verify checks every disconnected claim by a search from its start") {
  testing::TempDir dir;
  const auto instance = GraphReader::open(write_chain(dir.path()), VerifyLevel::full);
  SolutionWriter w(instance, "V");
  w.set_query(1, QueryStatus::disconnected, {});  // 0 cannot reach 4: true
  w.set_query(2, QueryStatus::disconnected, {});  // 3 reaches nothing: true
  w.write(dir / "right.sol.mosb");
  CHECK_FALSE(verify_solutions(SolutionReader::open(dir / "right.sol.mosb"), instance));
  w.set_query(3, QueryStatus::disconnected, {});  // 4 -> 0 -> 1 -> 2 -> 3: a wrong answer
  w.write(dir / "wrong.sol.mosb");
  const auto problem = verify_solutions(SolutionReader::open(dir / "wrong.sol.mosb"), instance);
  REQUIRE(problem.has_value());
  CHECK(*problem ==
        "query 3: [disconnected] the goal 3 is reachable from the start 4 (a wrong "
        "answer)");
}

TEST_CASE("format 1.5: the solver's reported runtime beside mosb's wall clock") {
  const auto instance = GraphReader::open(kSmall);
  const auto golden = kGolden / "1.5" / "solutions" / "valid" / "reported-runtime.sol.mosb";
  testing::TempDir dir;
  testing::write_golden_reported_runtime_solutions(instance, dir / "r.sol.mosb");
  CHECK_MESSAGE(testing::read_bytes(dir / "r.sol.mosb") == testing::read_bytes(golden),
                "the solution writer's output changed: if deliberate, update spec/SOLUTIONS.md "
                "and regenerate with mosb_make_golden solutions");
  const auto r = SolutionReader::open_verified(golden);
  CHECK(r.header().version_minor == 5);
  CHECK(r.has_statistic(Statistic::reported_runtime_seconds));
  CHECK(r.reported_runtime_seconds(0) == 0.125);
  CHECK_FALSE(r.reported_runtime_seconds(1));
  CHECK(r.runtime_seconds(1) == 0.25);
  CHECK(r.statistics(0).reported_runtime_seconds == 0.125);
  CHECK(r.statistic_as_double(Statistic::reported_runtime_seconds, 0) == 0.125);
  CHECK_FALSE(r.count_statistic(Statistic::reported_runtime_seconds, 0));
  // Without it a file keeps the minor it had: 1.3 with a view.
  SolutionWriter plain(instance, "Small_2");
  plain.write(dir / "plain.sol.mosb");
  CHECK(SolutionReader::open(dir / "plain.sol.mosb").header().version_minor == 3);
  // The writer refuses a reported runtime that is not a finite number >= 0, and one on a query
  // that may carry no statistics.
  SolutionWriter bad(instance, "Small_2");
  QueryStatistics negative;
  negative.reported_runtime_seconds = -1;
  CHECK_THROWS_WITH(bad.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25}, negative),
                    doctest::Contains("reported_runtime_seconds is not finite and >= 0"));
  QueryStatistics some;
  some.reported_runtime_seconds = 1;
  CHECK_THROWS_WITH(bad.set_query(2, QueryStatus::timeout, {}, some),
                    doctest::Contains("timeout carries no statistics"));
}

TEST_CASE("format 1.4: a solution file bound to its objectives alone, without a view") {
  const auto instance = GraphReader::open(kSmall);
  const auto golden = kGolden / "1.4" / "solutions" / "valid" / "objectives.sol.mosb";
  testing::TempDir dir;
  testing::write_golden_objective_solutions(instance, dir / "objectives.sol.mosb");
  CHECK_MESSAGE(testing::read_bytes(dir / "objectives.sol.mosb") == testing::read_bytes(golden),
                "the solution writer's output changed: if deliberate, update spec/SOLUTIONS.md "
                "and regenerate with mosb_make_golden solutions");
  const auto r = SolutionReader::open(golden, instance);
  CHECK(r.header().version_minor == 4);
  CHECK(r.view_name().empty());
  CHECK_FALSE(r.metadata().get("solution.view").has_value());
  CHECK(r.objective_name(0) == "time");
  CHECK(r.instance_objectives(instance) ==
        std::vector<std::size_t>{instance.objective_index("time"),
                                 instance.objective_index("distance")});
  CHECK_FALSE(verify_solutions(r, GraphReader::open(kSmall, VerifyLevel::full)).has_value());
  // A file with a view stays 1.3: readable by 1.3 readers.
  CHECK(SolutionReader::open(kSolutions / "valid" / "small.sol.mosb").header().version_minor == 3);

  SUBCASE("before 1.4 a file without solution.view is refused") {
    auto bytes = testing::read_bytes(golden);
    auto header = testing::header_of(bytes);
    header.version_minor = 3;
    testing::set_header(bytes, header);
    testing::reseal_header(bytes);
    testing::write_bytes(dir / "old.sol.mosb", bytes);
    CHECK_THROWS_WITH_AS(SolutionReader::open(dir / "old.sol.mosb"),
                         doctest::Contains("metadata has no 'solution.view'"), Error);
  }
}

TEST_CASE("an import's dropped vectors: recorded, read back, added up by merge, never an input") {
  // Issue 33 §4 and §5: solution.import.* says what `solutions import --nondominated` left out;
  // merge adds up its parts' and refuses to write over one of them.
  const auto instance = GraphReader::open(kSmall);
  testing::TempDir dir;
  const auto part = [&](const char* name, std::uint64_t q, std::optional<DroppedVectors> drop) {
    SolutionWriter w(instance, "Small_2");
    const std::vector<double> front{1, 9, 2, 7};
    w.set_query(q, QueryStatus::solved, front);
    w.set_dropped_vectors(drop);
    w.write(dir / name);
    return dir / name;
  };
  const auto a = part("a.sol", 0, DroppedVectors{3, 1});
  const auto b = part("b.sol", 1, DroppedVectors{5, 2});
  const auto c = part("c.sol", 2, std::nullopt);
  CHECK(SolutionReader::open(a).dropped_vectors() == DroppedVectors{3, 1});
  CHECK_FALSE(SolutionReader::open(c).dropped_vectors());
  const std::vector<std::filesystem::path> parts{a, b, c};
  const SolutionMerge merge(parts);
  const auto before = testing::read_bytes(b);
  CHECK_THROWS_WITH_AS(merge.write(b), doctest::Contains("refusing to overwrite an input"), Error);
  CHECK(testing::read_bytes(b) == before);
  merge.write(dir / "all.sol");
  CHECK(SolutionReader::open(dir / "all.sol").dropped_vectors() == DroppedVectors{8, 3});
  // A damaged record is an error, not a number.
  const auto bytes = testing::read_bytes(a);
  auto text = std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  const auto at = text.find("solution.import.dropped_vectors=3");
  REQUIRE(at != std::string::npos);
  text[at + std::string("solution.import.dropped_vectors=").size()] = 'x';
  const auto forged =
      SolutionReader::from_memory(std::as_bytes(std::span(text.data(), text.size())), "forged");
  CHECK_THROWS_AS(forged.dropped_vectors(), Error);
}

// ---- format 1.6: packed solution files (spec/SOLUTIONS.md §1) ----

namespace {
const auto kPackedSolutions = kGolden / "1.6" / "solutions";
}  // namespace

TEST_CASE("format 1.6: a packed solution file reads as its unpacked form and packs back") {
  const auto instance = GraphReader::open(kSmall);
  const auto golden = kPackedSolutions / "valid" / "fronts.packed.sol.mosb";
  testing::TempDir dir;
  testing::write_golden_packable_solutions(instance, dir / "plain.sol.mosb");
  const auto plain = SolutionReader::open_verified(dir / "plain.sol.mosb");
  CHECK(plain.header().version_minor == 5);
  const auto bytes = testing::read_bytes(golden);
  format::FileHeader stored{};
  std::memcpy(&stored, bytes.data(), sizeof stored);
  CHECK(stored.version_minor == format::kSolutionPackedMinor);
  CHECK(format::is_packed(stored));
  // Read through its decoded form: the values, the binding and the digest of the unpacked file.
  const auto packed = SolutionReader::open_verified(golden);
  CHECK(packed.header().version_minor == 5);
  CHECK(packed.digest() == plain.digest());
  CHECK(packed.vector_count() == 257);
  CHECK(packed.reported_runtime_seconds(0) == 0.125);
  CHECK_FALSE(verify_solutions(packed, GraphReader::open(kSmall, VerifyLevel::full)));
  // Unpacking restores the written bytes; packing them again, the golden bytes.
  CHECK(unpack_file(golden, dir / "back.sol.mosb") == plain.digest());
  CHECK(testing::read_bytes(dir / "back.sol.mosb") == testing::read_bytes(dir / "plain.sol.mosb"));
  CHECK(pack_file(dir / "plain.sol.mosb", dir / "again.sol.mosb", {}) == plain.digest());
  CHECK_MESSAGE(testing::read_bytes(dir / "again.sol.mosb") == bytes,
                "mosb pack no longer reproduces the golden packed solution file: a change of the "
                "packer, the writer or libzstd's output");
}

TEST_CASE("every invalid packed golden solution file is refused where EXPECTED.tsv says") {
  testing::TempDir dir;
  std::size_t cases = 0;
  for (const auto& row : testing::expected_rows(kPackedSolutions / "invalid" / "EXPECTED.tsv")) {
    REQUIRE(row.size() == 2);
    CAPTURE(row[0]);
    ++cases;
    const auto path = kPackedSolutions / "invalid" / row[0];
    CHECK_THROWS_WITH_AS(SolutionReader::open(path), doctest::Contains(row[1].c_str()), Error);
    CHECK_THROWS_WITH_AS(unpack_file(path, dir / "out.sol.mosb"), doctest::Contains(row[1].c_str()),
                         Error);
    CHECK_FALSE(std::filesystem::exists(dir / "out.sol.mosb"));
  }
  CHECK(cases == std::size(testing::kPackedSolutionFaults));
}

TEST_CASE("pack and unpack restore each layout's minor, and others have no packed form") {
  const auto instance = GraphReader::open(kSmall);
  testing::TempDir dir;
  std::vector<double> front;
  for (int i = 0; i < 128; ++i) {
    front.push_back(60 + i);
    front.push_back(300 - i);
  }
  // 1.3 with a view, 1.4 bound to its objectives alone.
  SolutionWriter with_view(instance, "Small_2");
  with_view.set_query(0, QueryStatus::solved, front);
  with_view.write(dir / "3.sol.mosb");
  SolutionWriter no_view(
      instance,
      View{
          "", {instance.objective_index("distance"), instance.objective_index("time")}, "default"});
  no_view.set_query(0, QueryStatus::solved, front);
  no_view.write(dir / "4.sol.mosb");
  for (const std::uint16_t minor : {3, 4}) {
    CAPTURE(minor);
    const auto name = std::to_string(minor) + ".sol.mosb";
    CHECK(SolutionReader::open(dir / name).header().version_minor == minor);
    pack_file(dir / name, dir / ("packed-" + name), {});
    CHECK(testing::read_bytes(dir / ("packed-" + name))[14] == std::byte{6});
    CHECK(SolutionReader::open(dir / ("packed-" + name)).header().version_minor == minor);
    unpack_file(dir / ("packed-" + name), dir / ("back-" + name));
    CHECK(testing::read_bytes(dir / ("back-" + name)) == testing::read_bytes(dir / name));
  }
  // A file before path sums (1.1), and one stating another minor than its content gives, could
  // not be restored: refused, nothing written.
  CHECK_THROWS_WITH_AS(
      pack_file(kOldSolutions / "valid" / "small.sol.mosb", dir / "old.sol.mosb", {}),
      doctest::Contains("has no packed form"), Error);
  auto bytes = testing::read_bytes(dir / "3.sol.mosb");
  auto header = testing::header_of(bytes);
  header.version_minor = 6;
  testing::set_header(bytes, header);
  testing::reseal_header(bytes);
  testing::write_bytes(dir / "six.sol.mosb", bytes);
  CHECK(SolutionReader::open(dir / "six.sol.mosb").header().version_minor == 6);
  CHECK_THROWS_WITH_AS(pack_file(dir / "six.sol.mosb", dir / "out.sol.mosb", {}),
                       doctest::Contains("not the minor the mosb writer gives its content"), Error);
  CHECK_FALSE(std::filesystem::exists(dir / "old.sol.mosb"));
  CHECK_FALSE(std::filesystem::exists(dir / "out.sol.mosb"));
}

TEST_CASE("open_verified_all opens in path order and throws the first failure in that order") {
  testing::TempDir dir;
  const auto good = kSolutions / "valid" / "small.sol.mosb";
  std::vector<std::filesystem::path> paths(6, good);
  paths.push_back(dir / "missing-1.sol.mosb");
  paths.push_back(dir / "missing-2.sol.mosb");
  for (const unsigned threads : {1U, 2U, 8U}) {
    CAPTURE(threads);
    const auto opened = open_verified_all(std::span(paths).first(6), threads);
    REQUIRE(opened.size() == 6);
    for (const auto& r : opened) CHECK(r.display_name() == good.string());
    CHECK_THROWS_WITH_AS(open_verified_all(paths, threads), doctest::Contains("missing-1"), Error);
  }
  CHECK(open_verified_all({}).empty());
}
