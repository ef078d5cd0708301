#include "mosb/converters/netmaker_generator.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "file_patch.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/converters/suite.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/manifest.hpp"
#include "mosb/pack.hpp"
#include "mosb/verify.hpp"
#include "requirements.hpp"
#include "temp_dir.hpp"

using namespace mosb;
using converters::NetMakerParameters;

namespace {

NetMakerParameters paper_parameters(std::uint64_t seed) {
  NetMakerParameters p;
  p.vertices = 10000;
  p.amin = 1;
  p.amax = 10;
  p.locality = 20;
  p.seed = seed;
  return p;
}

// Every vertex reached from 0 along forward (or reverse) arcs.
bool reaches_all(const GraphReader& r, bool reverse) {
  const auto off = reverse ? r.reverse_offsets() : r.forward_offsets();
  const auto next = reverse ? r.reverse_sources() : r.forward_targets();
  std::vector<bool> seen(r.vertex_count(), false);
  std::vector<std::uint32_t> stack{0};
  seen[0] = true;
  std::size_t count = 1;
  while (!stack.empty()) {
    const auto u = stack.back();
    stack.pop_back();
    for (auto a = off[u]; a < off[u + 1]; ++a)
      if (!seen[next[a]]) {
        seen[next[a]] = true;
        ++count;
        stack.push_back(next[a]);
      }
  }
  return count == r.vertex_count();
}

double pearson(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = double(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= n, my /= n;
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxy / std::sqrt(sxx * syy);
}

// spec/GENERATORS.md, "NetMaker: expected correlation": a cycle arc's objective is one of three
// independent discrete uniforms (means m_k, variances s_k) chosen by a uniform permutation, so
// rho = -(V_m / 2) / (V_w + V_m) with V_m the variance of the means and V_w the mean variance.
double expected_cycle_correlation() {
  const std::array<std::array<double, 2>, 3> ranges = {{{1, 333}, {334, 666}, {667, 1000}}};
  double mean = 0, within = 0;
  std::array<double, 3> means{};
  for (std::size_t k = 0; k < 3; ++k) {
    const double count = ranges[k][1] - ranges[k][0] + 1;
    means[k] = (ranges[k][0] + ranges[k][1]) / 2;
    within += (count * count - 1) / 12 / 3;
    mean += means[k] / 3;
  }
  double between = 0;
  for (auto m : means) between += (m - mean) * (m - mean) / 3;
  return -(between / 2) / (within + between);
}

}  // namespace

TEST_CASE("a NetMaker graph follows the paper's construction (N=10000, A=1, B=10, I=20)") {
  testing::TempDir dir;
  write_graph(converters::generate_netmaker(paper_parameters(1)), dir / "n.mosb");
  auto r = GraphReader::open(dir / "n.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  const std::uint32_t n = 10000, half = 10;
  REQUIRE(r.vertex_count() == n);
  REQUIRE(r.objective_count() == 3);
  // Every vertex has its cycle arc plus T - 1 locality arcs, T uniform in {2..10}; a window of 21
  // ids always holds at least 9 candidates, so no vertex falls short: E[m] = N (1 + 5) = 60000.
  // Var(T) = (9^2 - 1) / 12, so the sum over N vertices has sd sqrt(N * 80 / 12) ~ 258: 5 sd.
  CHECK(std::abs(double(r.arc_count()) - 60000.0) < 1300);
  CHECK(std::abs(double(r.arc_count()) / n - 6.0) < 0.13);

  const auto off = r.forward_offsets();
  const auto tgt = r.forward_targets();
  const auto* kind_section = r.find(format::SectionKind::arc_data, "kind");
  REQUIRE(kind_section != nullptr);
  const auto kind = r.values<std::uint8_t>(*kind_section);
  std::vector<std::uint32_t> successor(n, n);
  std::vector<std::uint32_t> in_cycle(n, 0);
  std::vector<std::uint16_t> c[3];
  for (std::size_t j = 0; j < 3; ++j) {
    const auto col = r.cost<std::uint16_t>(j);
    c[j].assign(col.begin(), col.end());
  }
  bool locality_ok = true, costs_ok = true, one_cycle_arc = true, degree_ok = true;
  for (std::uint32_t u = 0; u < n; ++u) {
    std::set<std::uint32_t> heads;
    std::size_t cycle_arcs = 0, local_arcs = 0;
    for (auto a = off[u]; a < off[u + 1]; ++a) {
      const auto v = tgt[a];
      locality_ok &= heads.insert(v).second && v != u;  // no duplicates, no self-loops
      if (kind[a] == converters::kNetMakerCycleArc) {
        ++cycle_arcs;
        successor[u] = v;
        ++in_cycle[v];
        std::array<std::uint16_t, 3> sorted = {c[0][a], c[1][a], c[2][a]};
        std::sort(sorted.begin(), sorted.end());
        costs_ok &= sorted[0] >= 1 && sorted[0] <= 333 && sorted[1] >= 334 && sorted[1] <= 666 &&
                    sorted[2] >= 667 && sorted[2] <= 1000;
      } else {
        ++local_arcs;
        locality_ok &=
            kind[a] == converters::kNetMakerLocalityArc && (v > u ? v - u : u - v) <= half;
        for (std::size_t j = 0; j < 3; ++j) costs_ok &= c[j][a] >= 1 && c[j][a] <= 99;
      }
    }
    one_cycle_arc &= cycle_arcs == 1;
    degree_ok &= local_arcs >= 1 && local_arcs <= 9;
  }
  CHECK(locality_ok);
  CHECK(costs_ok);
  CHECK(one_cycle_arc);
  CHECK(degree_ok);
  // The cycle arcs form one directed cycle through all N vertices.
  std::uint32_t v = 0, steps = 0;
  do {
    v = successor[v];
    ++steps;
  } while (v != 0 && v < n && steps <= n);
  CHECK(steps == n);
  CHECK(std::count(in_cycle.begin(), in_cycle.end(), 1u) == n);
  CHECK(reaches_all(r, false));
  CHECK(reaches_all(r, true));

  const auto queries = r.queries("default");
  REQUIRE(queries.size() == 50);
  std::set<std::pair<std::uint32_t, std::uint32_t>> distinct;
  for (const auto& q : queries) {
    CHECK(q.start < 1000);
    CHECK(q.goal >= 9000);
    CHECK(q.goal < n);
    distinct.insert({q.start, q.goal});
  }
  CHECK(distinct.size() == 50);
  const auto& md = r.metadata();
  CHECK(md.get("view.NetMaker-10k_3.objectives") == "c1,c2,c3");
  CHECK(md.get("view.NetMaker-10k_3.queries") == "default");
  CHECK(md.get("family") == "synthetic");
  CHECK(md.get("id_base") == "0");
  CHECK(md.get("source.param.locality") == "20");
  CHECK(md.get("benchmark") == "NetMaker-N10000-I20");
}

TEST_CASE("NetMaker correlations: about -0.44 on cycle arcs, about 0 on locality arcs") {
  const double expected = expected_cycle_correlation();
  CHECK(expected == doctest::Approx(-4.0 / 9).epsilon(0.002));  // the continuous limit: -4/9
  CHECK(expected == doctest::Approx(-0.44).epsilon(0.02));      // the paper's figure

  testing::TempDir dir;
  write_graph(converters::generate_netmaker(paper_parameters(5)), dir / "n.mosb");
  auto r = GraphReader::open(dir / "n.mosb");
  const auto kind = r.values<std::uint8_t>(*r.find(format::SectionKind::arc_data, "kind"));
  std::array<std::vector<double>, 3> cycle, local;
  for (std::size_t j = 0; j < 3; ++j) {
    std::vector<double> col(r.arc_count());
    r.read_cost_as(j, col);
    for (std::size_t a = 0; a < col.size(); ++a)
      (kind[a] == 0 ? cycle : local)[j].push_back(col[a]);
  }
  REQUIRE(cycle[0].size() == 10000);
  // The sample correlation of n pairs has sd ~ (1 - rho^2) / sqrt(n): 0.008 for the 10000 cycle
  // arcs, 0.0045 for the ~50000 locality arcs; the bounds are 5 sd.
  for (const auto& pair : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
    const int x = pair.first, y = pair.second;  // not a binding: see pack_test.cpp
    CAPTURE(x);
    CAPTURE(y);
    CHECK(std::abs(pearson(cycle[x], cycle[y]) - expected) < 0.04);
    CHECK(std::abs(pearson(local[x], local[y])) < 0.023);
  }
}

TEST_CASE("NetMaker generation is deterministic, and the seed matters") {
  testing::TempDir dir;
  auto p = paper_parameters(3);
  p.vertices = 2000;
  write_graph(converters::generate_netmaker(p), dir / "a.mosb");
  write_graph(converters::generate_netmaker(p), dir / "b.mosb");
  p.seed = 4;
  write_graph(converters::generate_netmaker(p), dir / "c.mosb");
  CHECK(testing::read_bytes(dir / "a.mosb") == testing::read_bytes(dir / "b.mosb"));
  CHECK(testing::read_bytes(dir / "a.mosb") != testing::read_bytes(dir / "c.mosb"));
}

TEST_CASE("a narrow locality window limits the locality arcs and a huge one does not blow up") {
  testing::TempDir dir;
  NetMakerParameters p;
  p.vertices = 500;
  p.locality = 1;  // floor(1/2) = 0: the window is {u}, no locality arc is possible
  write_graph(converters::generate_netmaker(p), dir / "one.mosb");
  CHECK(GraphReader::open(dir / "one.mosb").arc_count() == 500);
  p.locality = 2;  // at most u-1 and u+1
  write_graph(converters::generate_netmaker(p), dir / "two.mosb");
  auto r = GraphReader::open(dir / "two.mosb");
  const auto off = r.forward_offsets();
  for (std::uint32_t u = 0; u < 500; ++u) CHECK(off[u + 1] - off[u] <= 3);
  p.locality = 4000000000u;  // every other vertex is a candidate; candidates are never materialized
  write_graph(converters::generate_netmaker(p), dir / "all.mosb");
  CHECK_FALSE(verify(GraphReader::open(dir / "all.mosb"), VerifyLevel::full).has_value());
}

TEST_CASE("NetMaker parameters out of range are errors") {
  NetMakerParameters p;
  p.vertices = 1;
  CHECK_THROWS_AS(converters::generate_netmaker(p), Error);
  p.vertices = 100;
  p.amin = 10;
  p.amax = 10;
  CHECK_THROWS_AS(converters::generate_netmaker(p), Error);
  p.amin = 1;
  p.queries = 101;  // 10 sources x 10 targets: only 100 distinct pairs
  CHECK_THROWS_WITH_AS(converters::generate_netmaker(p), doctest::Contains("only 100"), Error);
}

TEST_CASE("a suite's files and MANIFEST do not depend on the thread count") {
  testing::TempDir dir;
  const auto instances = converters::netmaker_suite(7, {300});
  REQUIRE(instances.size() == 4);
  const auto one = converters::run_suite(dir / "one", instances, {1, {}, {}});
  std::size_t progress_calls = 0;
  const auto three =
      converters::run_suite(dir / "three", instances,
                            {3,
                             [&](std::string_view stage, std::uint64_t done, std::uint64_t total) {
                               CHECK(stage == "suite");
                               CHECK(done == progress_calls++);
                               CHECK(total == 4);
                             },
                             {}});
  CHECK(progress_calls == 5);
  REQUIRE(one.size() == 4);
  for (std::size_t i = 0; i < 4; ++i) {
    CHECK(one[i].name == three[i].name);
    CHECK(one[i].digest == three[i].digest);
    CHECK(testing::read_bytes(dir / "one" / one[i].file) ==
          testing::read_bytes(dir / "three" / one[i].file));
  }
  CHECK(testing::read_bytes(dir / "one" / "MANIFEST") ==
        testing::read_bytes(dir / "three" / "MANIFEST"));
  CHECK(one[0].name == "NetMaker-N300-I20-1");
  CHECK(one[3].name == "NetMaker-N300-I50-2");
  const auto manifest = read_manifest(dir / "one" / "MANIFEST");
  REQUIRE(manifest.entries.size() == 4);
  CHECK(manifest.entries[0].benchmark == one[0].name);
  CHECK(manifest.entries[0].file == one[0].file);
  CHECK(manifest.entries[0].size == one[0].size);
  CHECK(manifest.entries[0].digest == one[0].digest);
  // A view per size, as the paper's Table 1 splits NetMaker: 300 vertices, no thousands.
  CHECK(manifest.entries[0].views == std::vector<std::string>{"NetMaker-300_3"});
  CHECK(one[0].size == std::filesystem::file_size(dir / "one" / one[0].file));
}

TEST_CASE(
    "a suite subset reproduces the full suite's instance and a failing instance stops the suite") {
  testing::TempDir dir;
  const auto entries =
      converters::run_suite(dir / "s", converters::grid_suite(1, {30, 20, 30}), {2, {}, {}});
  REQUIRE(entries.size() == 4);  // 20x20, 20x30, 30x20, 30x30: the repeated size counts once
  CHECK(entries[1].name == "Grid-20x30");
  const auto seed = converters::suite_instance_seed(1, (std::uint64_t{20} << 20) + 30);
  write_graph(converters::generate_grid({20, 30, 3, seed}), dir / "single.mosb");
  CHECK(GraphReader::open(dir / "single.mosb").digest() == entries[1].digest);

  std::vector<converters::SuiteInstance> broken = {
      {"good",
       [] {
         return converters::generate_grid({5, 5, 3, 1});
       }},
      {"bad", []() -> GraphInput { throw Error("bad instance"); }}};
  CHECK_THROWS_WITH_AS(converters::run_suite(dir / "b", broken, {2, {}, {}}), "bad instance",
                       Error);
  CHECK_FALSE(std::filesystem::exists(dir / "b" / "MANIFEST"));
}

TEST_CASE("a packed suite lists packed files that unpack to the unpacked suite's bytes") {
  testing::TempDir dir;
  const auto instances = converters::grid_suite(1, {12, 15});
  const auto plain = converters::run_suite(dir / "plain", instances, {2, {}, {}});
  const auto packed = converters::run_suite(dir / "packed", instances, {2, {}, PackOptions{3, 1}});
  const auto manifest = read_manifest(dir / "packed" / "MANIFEST");
  REQUIRE(packed.size() == plain.size());
  REQUIRE(manifest.entries.size() == plain.size());
  for (std::size_t i = 0; i < plain.size(); ++i) {
    CHECK(packed[i].digest == plain[i].digest);
    CHECK(manifest.entries[i].packed);
    CHECK(manifest.entries[i].size == std::filesystem::file_size(dir / "packed" / packed[i].file));
    CHECK(packed[i].size < plain[i].size);
    unpack_file(dir / "packed" / packed[i].file, dir / "back.mosb");
    CHECK(testing::read_bytes(dir / "back.mosb") ==
          testing::read_bytes(dir / "plain" / plain[i].file));
  }
}

TEST_CASE("the real NetMaker file converts to 10000 vertices, 59750 arcs, 3 objectives") {
  const auto file =
      testing::shared_data() / "netmaker" / "netMaker_3o_10000n_1amin_10amax_20i_1s_scorr_79134.gr";
  testing::require_shared(file);
  testing::TempDir dir;
  write_graph(converters::convert_netmaker(file, std::nullopt), dir / "n.mosb");
  auto r = GraphReader::open(dir / "n.mosb");
  CHECK_FALSE(verify(r, VerifyLevel::full).has_value());
  CHECK(r.vertex_count() == 10000);
  CHECK(r.arc_count() == 59750);
  CHECK(r.objective_count() == 3);
  CHECK(r.metadata().get("family") == "synthetic");
  CHECK(r.metadata().get("id_base") == "0");
  CHECK(r.metadata().get("view.NetMaker-10k_3.objectives") == "c1,c2,c3");
  CHECK_FALSE(r.metadata().get("view.NetMaker-10k_3.queries").has_value());
  CHECK(r.metadata().get("benchmark") == "netMaker_3o_10000n_1amin_10amax_20i_1s_scorr_79134");
  CHECK(reaches_all(r, false));
  CHECK(reaches_all(r, true));
}

TEST_CASE("a streamed NetMaker graph is byte-identical to the one built in memory") {
  testing::TempDir dir;
  auto p = paper_parameters(2);
  for (const auto& [n, locality, amax] :
       {std::tuple{2000u, 20u, 10u}, std::tuple{300u, 100000u, 40u}, std::tuple{2u, 2u, 2u}}) {
    p.vertices = n;
    p.locality = locality;
    p.amax = amax;
    p.queries = 1;
    write_graph(converters::netmaker_graph(p), dir / "streamed.mosb");
    write_graph(converters::generate_netmaker(p), dir / "built.mosb");
    CHECK(testing::read_bytes(dir / "streamed.mosb") == testing::read_bytes(dir / "built.mosb"));
    CHECK_FALSE(verify(GraphReader::open(dir / "streamed.mosb"), VerifyLevel::full).has_value());
  }
}
