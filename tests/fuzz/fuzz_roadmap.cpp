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
    for (std::size_t v = 0; v < g.node_count(); ++v)
      for (std::size_t k = 0; k < g.node_keys.size(); ++k) (void)g.node_value(v, k);
    for (std::size_t e = 0; e < g.edges.size(); ++e) {
      const auto& edge = g.edges[e];
      if (edge.source >= g.node_count() || edge.target >= g.node_count()) __builtin_trap();
      for (std::size_t k = 0; k < g.edge_keys.size(); ++k) (void)g.edge_value(e, k);
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
