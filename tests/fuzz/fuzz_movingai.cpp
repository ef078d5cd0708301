// libFuzzer target: the Moving AI map and scenario parsers, the GUARDS guard and exposure parsers,
// and the octile graph both converters build. The input is split at 0x01 bytes into map, scenario,
// guards and exposure text; the later parts are read against the parsed map (or a fixed 3 x 2 map
// when the first part is not one).
// Any outcome but a clean mosb::Error or success is a bug.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mosb/converters/guards_converter.hpp"
#include "mosb/converters/movingai.hpp"
#include "mosb/error.hpp"

using namespace mosb::converters;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  std::vector<std::string_view> parts;
  for (std::size_t start = 0;;) {
    const auto end = all.find('\x01', start);
    parts.push_back(
        all.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos || parts.size() == 4) break;
    start = end + 1;
  }
  parts.resize(4);
  static const std::string name = "fuzz";
  static const OctileMap fixed =
      parse_octile_map("type octile\nheight 2\nwidth 3\nmap\n...\n.@.\n", name);
  OctileMap map = fixed;
  for (const bool swamp : {false, true}) {
    try {
      map = parse_octile_map(parts[0], name, {swamp, !swamp});
      if (map.passable.size() != std::size_t{map.width} * map.height) __builtin_trap();
    } catch (const mosb::Error&) {
    }
  }
  // Exposure is quadratic in the map size: keep the fuzzer fast.
  const bool small = map.passable.size() <= 4096;
  try {
    const auto entries = parse_scenario(parts[1], name);
    check_scenario(entries, name, map, name);
  } catch (const mosb::Error&) {
  }
  std::vector<std::uint64_t> exposure(map.passable.size(), 0);
  try {
    const auto guards = parse_guards(parts[2], name, map);
    for (const auto& g : guards)
      if (g.x >= map.width || g.y >= map.height || !map.is_passable(g.x, g.y)) __builtin_trap();
    if (small && guards.size() <= 16) exposure = compute_exposure(map, guards);
  } catch (const mosb::Error&) {
  }
  try {
    exposure = parse_exposure(parts[3], name, map);
  } catch (const mosb::Error&) {
  }
  if (small) {
    const auto arcs_of = [](const mosb::StreamedGraph& graph) {
      std::vector<std::pair<std::uint32_t, std::uint32_t>> arcs;
      graph.replay_arcs([&](std::uint32_t tail, std::uint32_t head) {
        if (tail >= graph.vertex_count || head >= graph.vertex_count) __builtin_trap();
        arcs.emplace_back(tail, head);
      });
      if (arcs.size() != graph.arc_count) __builtin_trap();
      return arcs;
    };
    const auto graph = build_guards_graph(map, exposure);
    // `convert movingai`'s graph is the same graph with the length alone.
    const auto plain = build_octile_graph(map);
    if (arcs_of(plain) != arcs_of(graph) || plain.costs.size() != 1) __builtin_trap();
  }
  return 0;
}
