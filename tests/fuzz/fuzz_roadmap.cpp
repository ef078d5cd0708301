// libFuzzer target: arbitrary bytes through the roadmap text parsers (GraphML reader, vertex file).
// Any outcome but a clean mosb::Error or success is a bug.
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/converters/graphml_reader.hpp"
#include "mosb/converters/roadmap_converter.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.xml";
  try {
    const auto g = mosb::converters::parse_graphml(text, name);
    if (g.node_data.size() != g.node_ids.size()) __builtin_trap();
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      const auto& edge = g.edges[e];
      if (edge.source >= g.node_ids.size() || edge.target >= g.node_ids.size()) __builtin_trap();
      if (edge.data.size() != g.edge_keys.size()) __builtin_trap();
      (void)g.describe_edge(e);
    }
  } catch (const mosb::Error&) {
  }
  try {
    const auto vf = mosb::converters::parse_vertex_file(text, "fuzz.txt");
    if (vf.coords.size() != vf.ids.size() * vf.dof || vf.lines.size() != vf.ids.size())
      __builtin_trap();
  } catch (const mosb::Error&) {
  }
  return 0;
}
