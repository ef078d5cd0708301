#include "mosb/converters/roadmap_converter.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "mosb/converters/graphml_reader.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"
#include "requirements.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;
using converters::ClearanceMode;
using converters::RoadmapOptions;

namespace {

using namespace mosb::testing;  // write_text, slurp

GraphReader convert(const RoadmapOptions& o, const std::filesystem::path& out) {
  write_graph(converters::convert_roadmap(o), out);
  auto reader = GraphReader::open(out);
  REQUIRE_FALSE(verify(reader, VerifyLevel::full).has_value());
  return reader;
}

std::vector<double> costs(const GraphReader& g, std::string_view name) {
  std::vector<double> v(g.arc_count());
  g.read_cost_as(g.objective_index(name), v);
  return v;
}

std::string error_of(const RoadmapOptions& o) {
  try {
    (void)converters::convert_roadmap(o);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

// Three vertices: a = (0,0), b = (3,4), c = (3,0); undirected edges a-b (length 5) and b-c (length
// 4). Link clearances: a-b (0.05, 0.2), b-c (0.5, 0.01). With delta 0.1: U(0.05) = 0.05^2/0.2 =
// 0.0125, U(0.01) = 0.09^2/0.2 = 0.0405, U(0.2) = U(0.5) = 0.
std::string graphml(const std::string& bc_link0 = "0.5") {
  return R"(<?xml version="1.0" encoding="UTF-8"?>
<graphml xmlns="http://graphml.graphdrawing.org/xmlns">
  <key id="w" for="edge" attr.name="weight" attr.type="double"><default>7</default></key>
  <key id="d1" for="edge" attr.name="clearance_1" attr.type="double"/>
  <key id="q" for="node" attr.name="coords" attr.type="string"/>
  <key id="d0" for="edge" attr.name="clearance_0" attr.type="double"/>
  <graph id="G" edgedefault="undirected">
    <edge id="e0" source="a" target="b"><data key="d0">0.05</data><data key="d1">0.2</data></edge>
    <node id="a"><data key="q">0,0</data></node>
    <node id="b"><data key="q"> 3, 4 </data></node>
    <node id="c"><data key="q">3,0</data></node>
    <edge id="e1" source="b" target="c"><data key="d0">)" +
         bc_link0 + R"(</data><data key="d1">0.01</data>
      <data key="w">2.5</data></edge>
  </graph>
</graphml>
)";
}

}  // namespace

TEST_CASE("clearance penalty follows the paper's U(d)") {
  CHECK(converters::clearance_penalty(0.1, 0.1) == 0.0);
  CHECK(converters::clearance_penalty(3.0, 0.1) == 0.0);
  CHECK(converters::clearance_penalty(0.05, 0.1) == doctest::Approx(0.0125).epsilon(1e-12));
  CHECK(converters::clearance_penalty(0.01, 0.1) == doctest::Approx(0.0405).epsilon(1e-12));
  CHECK(converters::clearance_penalty(0.5, 1.0) == doctest::Approx(0.125).epsilon(1e-12));
}

TEST_CASE("GraphML roadmap: aggregate clearance, undirected edges as two arcs") {
  testing::TempDir dir;
  write_text(dir / "r.graphml", graphml());
  RoadmapOptions o;
  o.graphml_file = (dir / "r.graphml").string();
  o.clearance = ClearanceMode::aggregate;
  const auto g = convert(o, dir / "r.mosb");
  CHECK(g.vertex_count() == 3);
  REQUIRE(g.arc_count() == 4);  // a>b, b>a, b>c, c>b
  CHECK(std::vector<std::uint32_t>(g.forward_targets().begin(), g.forward_targets().end()) ==
        std::vector<std::uint32_t>{1, 0, 2, 1});
  REQUIRE(g.objective_count() == 2);
  CHECK(g.objective(0).name == "length");
  const auto length = costs(g, "length");
  CHECK(length == std::vector<double>{5, 5, 4, 4});
  const auto clearance = costs(g, "clearance");
  CHECK(clearance[0] == doctest::Approx(0.0125).epsilon(1e-12));
  CHECK(clearance[1] == doctest::Approx(0.0125).epsilon(1e-12));
  CHECK(clearance[2] == doctest::Approx(0.0405).epsilon(1e-12));
  CHECK(clearance[3] == doctest::Approx(0.0405).epsilon(1e-12));
  const auto& m = g.metadata();
  CHECK(m.get("view.Panda-RRG_2.objectives") == "length,clearance");
  CHECK(m.get("family") == "robots");
  CHECK(m.get("source.param.clearance") == "aggregate");
  CHECK(m.get("source.param.delta") == "0.1");
  CHECK(m.get("roadmap.edgedefault") == "undirected");
  const auto* config = g.find(format::SectionKind::vertex_data, "config");
  REQUIRE(config != nullptr);
  CHECK(config->entry.row_width == 2);
  const auto q = g.values<double>(*config);
  CHECK(std::vector<double>(q.begin(), q.end()) == std::vector<double>{0, 0, 3, 4, 3, 0});
}

TEST_CASE("GraphML roadmap: per-link clearance, weight, delta and objective names") {
  testing::TempDir dir;
  write_text(dir / "r.graphml", graphml());
  RoadmapOptions o;
  o.graphml_file = (dir / "r.graphml").string();
  o.clearance = ClearanceMode::per_link;
  o.weight = true;
  const auto g = convert(o, dir / "r.mosb");
  REQUIRE(g.objective_count() == 4);
  CHECK(g.objective(1).name == "clearance_0");
  CHECK(g.objective(3).name == "weight");
  const auto l0 = costs(g, "clearance_0"), l1 = costs(g, "clearance_1");
  CHECK(l0[0] == doctest::Approx(0.0125).epsilon(1e-12));
  CHECK(l0[2] == 0.0);
  CHECK(l1[0] == 0.0);
  CHECK(l1[3] == doctest::Approx(0.0405).epsilon(1e-12));
  CHECK(costs(g, "weight") == std::vector<double>{7, 7, 2.5, 2.5});  // e0 takes the key's default
  CHECK_FALSE(g.metadata().get("view.Panda-RRG_2.objectives").has_value());

  o.delta = 1.0;  // U(0.5) = 0.5^2 / 2 = 0.125 on link 0 of b-c
  o.objectives = {{"len", "rad"}, {"p0", ""}, {"p1", ""}, {"w", ""}};
  const auto h = convert(o, dir / "r2.mosb");
  CHECK(costs(h, "p0")[2] == doctest::Approx(0.125).epsilon(1e-12));
  CHECK(h.metadata().get("objective.len.unit") == "rad");

  o.objectives.pop_back();
  CHECK(error_of(o).find("3 objective names given, the input has 4") != std::string::npos);
}

TEST_CASE("GraphML roadmap: a collision edge is refused, naming the edge") {
  testing::TempDir dir;
  write_text(dir / "r.graphml", graphml("0"));
  RoadmapOptions o;
  o.graphml_file = (dir / "r.graphml").string();
  o.clearance = ClearanceMode::per_link;
  CHECK(error_of(o) ==
        (dir / "r.graphml").string() +
            ": edge 'e1' ('b' -> 'c'): clearance_0 = 0 <= 0: a collision (roadmap edges must be "
            "collision-free)");
  o.clearance = ClearanceMode::aggregate;  // the minimum over links is the colliding one
  CHECK(error_of(o).find("edge 'e1' ('b' -> 'c'): clearance_0 = 0 <= 0") != std::string::npos);
  write_text(dir / "r.graphml", graphml("-0.25"));
  CHECK(error_of(o).find("clearance_0 = -0.25 <= 0: a collision") != std::string::npos);
}

TEST_CASE("GraphML roadmap: malformed documents give one-line errors") {
  const std::string name = "x.graphml";
  const auto message = [&](const std::string& text) {
    try {
      (void)converters::parse_graphml(text, name);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  CHECK(message("<graphml><graph edgedefault='directed'>").find("x.graphml:1: XML error") == 0);
  CHECK(message(std::string(200, '<')).find("x.graphml") == 0);
  std::string deep;
  for (int i = 0; i < 100; ++i) deep += "<a>";
  CHECK(message(deep) == "x.graphml: elements nested deeper than 64 levels");
  CHECK(message("<graphml><graph edgedefault='directed'><node id='a'/><edge source='a' "
                "target='z'/></graph></graphml>") == "x.graphml: edge #0: target 'z' is no node");
  CHECK(message("<graphml><graph edgedefault='directed'><node id='a'><data "
                "key='k'>1</data></node></graph></graphml>") ==
        "x.graphml: node 'a': <data key='k'> names no key declared for it");
  CHECK(message("<graphml><graph><node id='a'/></graph></graphml>") ==
        "x.graphml: <graph edgedefault=''>: expected 'directed' or 'undirected'");
  CHECK(message("<graphml><graph edgedefault='directed'><node id='a'/><node "
                "id='a'/></graph></graphml>") == "x.graphml: node id 'a' appears twice");
  const auto g = converters::parse_graphml(
      "<graphml><key id='c' for='all' attr.name='coords'/><graph edgedefault='directed'><node "
      "id='a'/>"
      "<edge source='a' target='a' directed='false'/></graph></graphml>",
      name);
  CHECK(g.node_keys.size() == 1);
  CHECK(g.edge_keys.size() == 1);
  REQUIRE(g.edges.size() == 1);
  CHECK_FALSE(g.edges[0].directed);
}

TEST_CASE(".gr roadmap: ids beyond the declared count, vertex file, determinism") {
  testing::TempDir dir;
  // Declares 3 vertices, uses ids 0..3 (like the real point-robot files).
  write_text(dir / "c1.gr", "c\np sp 3 3\na 0 1 1.5\na 2 3 2.25\na 3 0 0.5\n");
  write_text(dir / "c2.gr", "p sp 3 3\na 0 1 3\na 2 3 4\na 3 0 5\n");
  write_text(dir / "v.txt", "0 0 0\n1 3 4\n2 1 1\n3 -1 0.5\n");
  RoadmapOptions o;
  o.gr_files = {(dir / "c1.gr").string(), (dir / "c2.gr").string()};
  o.vertex_file = (dir / "v.txt").string();
  CHECK(error_of(o) ==
        (dir / "c1.gr").string() +
            ":4:5: the largest vertex id, 3, is outside the 3 vertices declared on line 2 (0-based "
            "ids 0..2); vertices_from_ids sizes the graph from the largest id instead");
  o.vertices_from_ids = true;
  const auto g = convert(o, dir / "a.mosb");
  CHECK(g.vertex_count() == 4);
  CHECK(g.arc_count() == 3);
  REQUIRE(g.objective_count() == 2);
  CHECK(costs(g, "c1") == std::vector<double>{1.5, 2.25, 0.5});
  CHECK(costs(g, "c2") == std::vector<double>{3, 4, 5});
  CHECK(g.metadata().get("warning.vertex_count") == "declared 3, ids reach 3");
  const auto* config = g.find(format::SectionKind::vertex_data, "config");
  REQUIRE(config != nullptr);
  const auto q = g.values<double>(*config);
  CHECK(std::vector<double>(q.begin(), q.end()) == std::vector<double>{0, 0, 3, 4, 1, 1, -1, 0.5});
  convert(o, dir / "b.mosb");
  CHECK(slurp(dir / "a.mosb") == slurp(dir / "b.mosb"));

  // Only the vertex file goes beyond the declared count.
  write_text(dir / "c3.gr", "p sp 4 1\na 0 1 1\n");
  write_text(dir / "v5.txt", "0 0\n1 0\n2 0\n3 0\n4 0\n");
  RoadmapOptions p;
  p.gr_files = {(dir / "c3.gr").string()};
  p.vertex_file = (dir / "v5.txt").string();
  CHECK(error_of(p).find(
            "v5.txt:5:1: the largest vertex id, 4, is outside the 4 vertices declared on") !=
        std::string::npos);
  p.vertices_from_ids = true;
  CHECK(convert(p, dir / "c.mosb").vertex_count() == 5);

  write_text(dir / "v5.txt", "0 0\n1 0\n3 0\n");
  CHECK(error_of(p) == (dir / "v5.txt").string() + ": no line for vertex 2");
  write_text(dir / "v5.txt", "0 0\n1 0 2\n");
  CHECK(error_of(p) ==
        (dir / "v5.txt").string() + ":2:5: extra field '2': expected 1 coordinates as on line 1");
}

TEST_CASE("real point-robot roadmap and GraphML fixture") {
  const auto data = testing::shared_data();
  testing::require_shared(data / "roadmap-graphml/roadmap.xml");
  testing::TempDir dir;
  RoadmapOptions o;
  o.graphml_file = (data / "roadmap-graphml/roadmap.xml").string();
  o.weight = true;
  const auto g = convert(o, dir / "r.mosb");
  CHECK(g.vertex_count() == 170);
  CHECK(g.arc_count() == 698);  // edgedefault="directed", every edge listed in both directions
  CHECK(g.objective_count() == 2);
  CHECK(g.metadata().get("source.param.clearance") == "none");

  const auto exp = data / "roadmap-point-robot/exp_4_obs";
  RoadmapOptions p;
  for (int i = 0; i < 6; ++i)
    p.gr_files.push_back((exp / ("file_" + std::to_string(i) + ".gr")).string());
  p.vertex_file = (exp / "vertex_positions.txt").string();
  CHECK(
      error_of(p) ==
      p.gr_files[0] +
          ":146501:8: the largest vertex id, 5002, is outside the 5002 vertices declared on line 2 "
          "(0-based ids 0..5001); vertices_from_ids sizes the graph from the largest id instead");
}
