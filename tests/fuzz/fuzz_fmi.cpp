// libFuzzer target: arbitrary bytes through the FMI text parser in the standard layout and with ten
// costs (strict and skipping extra fields), then a BFS extraction of what parsed. Any outcome but a
// clean mosb::Error or success is a bug.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "mosb/converters/fmi_converter.hpp"
#include "mosb/error.hpp"

namespace {

void check(const mosb::converters::FmiGraph& g) {
  for (std::size_t k = 0; k < g.tails.size(); ++k)
    if (g.tails[k] >= g.vertex_count || g.heads[k] >= g.vertex_count) __builtin_trap();
  if (g.coords.size() != 2 * g.vertex_count || g.osm_ids.size() != g.vertex_count) __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.fmi";
  const std::optional<unsigned> layouts[] = {std::nullopt, 10u};
  for (const auto& costs : layouts)
    for (bool skip : {false, true}) {
      try {
        const auto g = mosb::converters::parse_fmi(text, name, costs, skip);
        check(g);
        if (g.vertex_count == 0) continue;
        const auto root = static_cast<std::uint32_t>(size % g.vertex_count);
        const auto selected = mosb::converters::bfs_select(g, root, 1 + size % 4, skip, name);
        check(mosb::converters::induced_subgraph(g, selected));
      } catch (const mosb::Error&) {
      }
    }
  return 0;
}
