#include "mosb/converters/grid_generator.hpp"

#include <doctest/doctest.h>

#include <array>
#include <cstdlib>

#include "file_patch.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "temp_dir.hpp"

using namespace mosb;

TEST_CASE("a grid has the paper's shape: 4-connected cells plus wired source and target") {
  testing::TempDir dir;
  const std::uint32_t K = 7, M = 5;
  write_graph(converters::generate_grid({K, M, 3, 11}), dir / "g.mosb");
  auto r = GraphReader::open(dir / "g.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  CHECK(r.vertex_count() == K * M + 2);
  CHECK(r.arc_count() == 2 * ((K - 1) * M + (M - 1) * K) + 2 * M);
  const auto off = r.forward_offsets();
  const auto tgt = r.forward_targets();
  const std::uint32_t source = K * M, target = K * M + 1;
  // Every cell arc joins 4-neighbours, and its reverse arc exists.
  for (std::uint32_t u = 0; u < K * M; ++u)
    for (auto a = off[u]; a < off[u + 1]; ++a) {
      const auto v = tgt[a];
      if (v == target) {
        CHECK(u % K == K - 1);
        continue;
      }
      const int dx = int(v % K) - int(u % K), dy = int(v / K) - int(u / K);
      CHECK(std::abs(dx) + std::abs(dy) == 1);
      bool back = false;
      for (auto b = off[v]; b < off[v + 1]; ++b) back |= tgt[b] == u;
      CHECK(back);
    }
  CHECK(off[source + 1] - off[source] == M);
  for (auto a = off[source]; a < off[source + 1]; ++a) CHECK(tgt[a] % K == 0);
  CHECK(off[target + 1] == off[target]);
  CHECK(r.reverse_offsets()[target + 1] - r.reverse_offsets()[target] == M);
  for (std::size_t j = 0; j < 3; ++j)
    for (auto c : r.cost<std::uint8_t>(j)) {
      CHECK(c >= 1);
      CHECK(c <= 10);
    }
  REQUIRE(r.queries("default").size() == 1);
  CHECK(r.queries("default")[0] == Query{source, target});
  CHECK(r.metadata().get("view.Grid_2.objectives") == "c1,c2");
  CHECK(r.metadata().get("view.Grid_3.objectives") == "c1,c2,c3");
}

TEST_CASE("grid generation is deterministic, and Grid_2 is a prefix of Grid_3") {
  testing::TempDir dir;
  write_graph(converters::generate_grid({20, 30, 3, 9}), dir / "a.mosb");
  write_graph(converters::generate_grid({20, 30, 3, 9}), dir / "b.mosb");
  write_graph(converters::generate_grid({20, 30, 2, 9}), dir / "two.mosb");
  write_graph(converters::generate_grid({20, 30, 3, 10}), dir / "other.mosb");
  CHECK(testing::read_bytes(dir / "a.mosb") == testing::read_bytes(dir / "b.mosb"));
  auto three = GraphReader::open(dir / "a.mosb");
  auto two = GraphReader::open(dir / "two.mosb");
  auto other = GraphReader::open(dir / "other.mosb");
  for (std::size_t j = 0; j < 2; ++j) {
    CHECK(three.objective(j).entry.checksum == two.objective(j).entry.checksum);
    CHECK(three.objective(j).entry.checksum != other.objective(j).entry.checksum);
  }
}

TEST_CASE("every cost value 1..10 appears about equally often") {
  testing::TempDir dir;
  write_graph(converters::generate_grid({100, 100, 1, 3}), dir / "g.mosb");
  auto r = GraphReader::open(dir / "g.mosb");
  std::array<std::size_t, 11> counts{};
  for (auto c : r.cost<std::uint8_t>(0)) ++counts[c];
  const double expected = double(r.arc_count()) / 10;  // ~3980 each, sd ~ 60
  for (int v = 1; v <= 10; ++v) CHECK(std::abs(double(counts[v]) - expected) < 400);
}

TEST_CASE("a streamed grid is byte-identical to the grid built in memory") {
  testing::TempDir dir;
  for (const converters::GridParameters& p :
       {converters::GridParameters{1, 1, 1, 2}, converters::GridParameters{7, 5, 3, 11},
        converters::GridParameters{20, 3, 16, 4, 1, 300},
        converters::GridParameters{9, 9, 2, 5, 0, 70000}}) {
    write_graph(converters::grid_graph(p), dir / "streamed.mosb");
    write_graph(converters::generate_grid(p), dir / "built.mosb");
    CHECK(testing::read_bytes(dir / "streamed.mosb") == testing::read_bytes(dir / "built.mosb"));
    CHECK_FALSE(verify(GraphReader::open(dir / "streamed.mosb"), VerifyLevel::full).has_value());
  }
}

TEST_CASE(
    "the streamed writer reports progress up to its total and refuses arcs out of tail order") {
  testing::TempDir dir;
  std::uint64_t last_done = 0, last_total = 0, calls = 0;
  write_graph(converters::grid_graph({30, 20, 3, 1}), dir / "g.mosb",
              [&](std::string_view stage, std::uint64_t done, std::uint64_t total) {
                CHECK(stage == "write");
                CHECK(done >= last_done);
                last_done = done;
                last_total = total;
                ++calls;
              });
  CHECK(calls >= 2);
  CHECK(last_done == last_total);
  CHECK(last_total == GraphReader::open(dir / "g.mosb").arc_count() * (4 + 2 * 3));

  StreamedGraph unordered;
  unordered.vertex_count = 3;
  unordered.arc_count = 2;
  unordered.replay_arcs = [](const StreamedGraph::ArcSink& arc) {
    arc(2, 0);
    arc(1, 0);
  };
  CHECK_THROWS_AS(write_graph(unordered, dir / "u.mosb"), Error);
  CHECK_FALSE(std::filesystem::exists(dir / "u.mosb"));
  StreamedGraph short_count = unordered;
  short_count.replay_arcs = [](const StreamedGraph::ArcSink& arc) { arc(0, 1); };
  CHECK_THROWS_AS(write_graph(short_count, dir / "s.mosb"), Error);
  StreamedGraph bad_head = unordered;
  bad_head.replay_arcs = [](const StreamedGraph::ArcSink& arc) {
    arc(0, 1);
    arc(1, 3);
  };
  CHECK_THROWS_WITH_AS(write_graph(bad_head, dir / "h.mosb"),
                       "arc 1 (1 -> 3) has an endpoint not below the vertex count 3", Error);
}

TEST_CASE("verify reports its progress in one stage, monotone, up to its total") {
  testing::TempDir dir;
  // Above 1 MiB, so the checks run on every core and report from several threads.
  write_graph(converters::grid_graph({300, 300, 3, 1}), dir / "g.mosb");
  const auto reader = GraphReader::open(dir / "g.mosb");
  std::uint64_t last_done = 0, last_total = 0, calls = 0;
  bool monotone = true, one_stage = true;
  const auto problem = verify(reader, VerifyLevel::full,
                              [&](std::string_view stage, std::uint64_t done, std::uint64_t total) {
                                one_stage = one_stage && stage == "verify";
                                monotone = monotone && done >= last_done && done <= total;
                                last_done = done;
                                last_total = total;
                                ++calls;
                              });
  CHECK_FALSE(problem.has_value());
  CHECK(one_stage);
  CHECK(monotone);
  CHECK(calls >= 3);
  CHECK(last_total > reader.bytes().size() / 2);
  CHECK(last_done == last_total);
}
