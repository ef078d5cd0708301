// Moving AI grid benchmarks (spec/families/games.md): octile maps (.map) and scenarios (.scen), the
// graph of an octile map, and `convert movingai` (the map alone, objective length).
// Every input error is one line "FILE:LINE:COLUMN: message".
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/format.hpp"
#include "mosb/graph_builder.hpp"

namespace mosb::converters {

// Which of the two terrain kinds whose reading depends on the agent count as passable.
struct TerrainRules {
  bool swamp_passable = true;   // 'S': "passable from regular terrain"
  bool water_passable = false;  // 'W': "traversable, but not passable from terrain"
};

// A parsed octile map. Cell (x, y) is column x, row y, row 0 being the first row of the file.
// The most cells (width x height) a map may have: one vertex per passable cell must fit the
// format's counts. The map converters and the instance map of `queries import --scen` apply it.
inline constexpr std::uint64_t kMaxOctileCells = format::kMaxCount;

struct OctileMap {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> passable;  // width*height flags, row-major: index y*width + x

  bool is_passable(std::uint32_t x, std::uint32_t y) const {
    return passable[std::size_t{y} * width + x] != 0;
  }
};

OctileMap parse_octile_map(std::string_view text, const std::string& display_name,
                           const TerrainRules& rules = {});

// One scenario row: `bucket map width height sx sy gx gy optimal`, tab-separated.
struct ScenarioEntry {
  std::uint64_t line = 0;
  std::uint64_t bucket = 0;
  std::string map;
  std::uint32_t map_width = 0, map_height = 0;
  std::uint32_t start_x = 0, start_y = 0, goal_x = 0, goal_y = 0;
  double optimal = 0;
  std::array<std::uint32_t, 9> columns{};  // 1-based column of each field, for messages
};

// Parses a `version 1` scenario file; blank lines are skipped.
std::vector<ScenarioEntry> parse_scenario(std::string_view text, const std::string& display_name);

// Throws "FILE:LINE:COLUMN: ..." when a row's width/height differ from the map's or its start or
// goal lies outside the map or on a blocked cell.
void check_scenario(const std::vector<ScenarioEntry>& entries, const std::string& display_name,
                    const OctileMap& map, const std::string& map_name);

// A per-cell value E turned into an arc objective (the GUARDS exposure): a move to cell d costs
// E(d), a diagonal move the largest of E(d) and E of its two side cells.
struct CellObjective {
  std::string name;
  std::string unit;
  std::shared_ptr<const std::vector<std::uint64_t>> values;  // row-major, like OctileMap::passable
};

// The graph of an octile map (spec/families/games.md §2): vertices the passable cells in row-major
// order (vertex data `cell` (x, y)), 8-connected arcs without corner cutting, objective `length`
// (10 / 14, unit `0.1 cell`), then the cell objective when given; metadata map.width, map.height.
// Streamed: the arcs are replayed from the map, never held (memory O(cells) + the reverse CSR).
StreamedGraph build_octile_graph(const OctileMap& map,
                                 const std::optional<CellObjective>& cell_objective = {});

// The vertex of each passable cell (row-major numbering), for rows already checked against the map:
// the query set `scen`, in file order, with each row's `optimal` as its reference for objective
// `length` (source `movingai-optimal`, spec/SOLUTIONS.md §6).
QuerySet scenario_queries(const std::vector<ScenarioEntry>& entries, const OctileMap& map);

struct MovingaiOptions {
  std::string map_file;
  std::optional<std::string> scen_file;
  TerrainRules terrain;
  std::optional<std::string> name;  // benchmark; default: the map's base name without ".map"
};

// Reads the inputs (decompressing as needed) and builds the one-objective instance; throws
// mosb::Error, also for a map without any passable cell.
StreamedGraph convert_movingai(const MovingaiOptions& options);

}  // namespace mosb::converters
