// libFuzzer target: the metadata a map figure reads (map.width, map.height, map.guards and the
// objectives' units; a download, so untrusted), on a 4 x 3 map of 11 cells whose file is
// otherwise valid, drawn as `mosb report` and `mosb plot map` draw it (map_of, the query markers,
// plot_map). The input is up to five lines: width, height, guards, the exposure's unit, the
// length's unit. Any outcome but a figure of at most max_side squares a side (its guards and
// markers on it), or a clean mosb::Error, is a bug; so is a run that does not end.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/report/figures.hpp"
#include "mosb/report/plots.hpp"

namespace {

// The instance without its fuzzed metadata: the passable cells of "....", ".@..", "...." in
// row-major order, an arc each way between orthogonal neighbours, length 10 and exposure x + y.
mosb::GraphInput small_map() {
  mosb::GraphInput g;
  std::vector<std::uint16_t> cells;
  for (std::uint16_t y = 0; y < 3; ++y)
    for (std::uint16_t x = 0; x < 4; ++x)
      if (x != 1 || y != 1) cells.insert(cells.end(), {x, y});
  g.vertex_count = cells.size() / 2;
  std::vector<std::uint64_t> length, exposure;
  for (std::size_t u = 0; u < g.vertex_count; ++u)
    for (std::size_t v = 0; v < g.vertex_count; ++v) {
      const int dx = cells[2 * u] - cells[2 * v], dy = cells[2 * u + 1] - cells[2 * v + 1];
      if (dx * dx + dy * dy != 1) continue;
      g.tails.push_back(static_cast<std::uint32_t>(u));
      g.heads.push_back(static_cast<std::uint32_t>(v));
      length.push_back(10);
      exposure.push_back(cells[2 * v] + cells[2 * v + 1]);
    }
  g.costs = {{"length", "", length, std::nullopt}, {"exposure", "", exposure, std::nullopt}};
  g.vertex_data.push_back(mosb::DataColumn::from("cell", 2, cells));
  g.queries.push_back({"q", {{0, 10}, {3, 7}}});
  g.metadata.set("family", "games");
  return g;
}

std::filesystem::path g_scratch;  // removed when the fuzzer exits

void remove_scratch() {
  std::error_code ignored;
  std::filesystem::remove_all(g_scratch, ignored);
}

const std::filesystem::path& scratch() {
  // tmpfs where there is one: each input writes a file (and fsyncs it).
  if (g_scratch.empty()) {
    std::string base = std::filesystem::exists("/dev/shm") ? "/dev/shm" : "/tmp";
    std::string name = base + "/mosb-fuzz-map-XXXXXX";
    if (::mkdtemp(name.data()) == nullptr) std::abort();
    g_scratch = name;
    std::atexit(remove_scratch);
  }
  return g_scratch;
}

void check_drawn(const mosb::plots::MapPlot& map, std::uint32_t max_side) {
  if (map.width == 0 || map.height == 0 || map.width > max_side || map.height > max_side ||
      map.passable.size() != std::size_t{map.width} * map.height)
    std::abort();
  for (const auto& g : map.guards)
    if (!(g.x >= 0 && g.x < map.width && g.y >= 0 && g.y < map.height)) std::abort();
  for (const auto& q : map.queries)
    if (!(q.start.x < map.width && q.start.y < map.height && q.goal.x < map.width &&
          q.goal.y < map.height))
      std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const mosb::GraphInput base = small_map();
  std::vector<std::string> fields;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  while (fields.size() < 5 && !text.empty()) {
    const auto end = text.find('\n');
    fields.emplace_back(text.substr(0, end));
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
  }
  fields.resize(5);
  auto g = base;
  const char* keys[] = {"map.width", "map.height", "map.guards"};
  g.costs[1].unit = fields[3];
  g.costs[0].unit = fields[4];
  const auto file = scratch() / "m.mosb";
  std::optional<mosb::GraphReader> opened;
  try {
    // Only a file that passes verify --level full is drawn: values the format does not allow
    // (invalid UTF-8, say) are refused here, by Metadata::set, the writer or the verifier.
    for (int k = 0; k < 3; ++k)
      if (!fields[k].empty()) g.metadata.set(keys[k], fields[k]);
    mosb::write_graph(g, file);
    opened.emplace(mosb::GraphReader::open(file, mosb::VerifyLevel::full));
  } catch (const mosb::Error&) {
    return 0;
  }
  const auto& reader = *opened;
  for (const std::uint32_t max_side : {3u, 160u, mosb::plots::kMapSideOfPlot}) {
    try {
      auto map = mosb::plots::map_of(reader, "exposure", max_side);
      const std::uint64_t queries[] = {0, 1, 5};
      mosb::plots::add_query_markers(map, reader, "q", queries);
      check_drawn(map, max_side);
      map.title = mosb::plots::axis_label("length", mosb::plots::objective_unit(reader, "length"));
      if (mosb::plots::plot_map(map).find("</svg>") == std::string::npos) std::abort();
    } catch (const mosb::Error&) {
    }
  }
  return 0;
}
