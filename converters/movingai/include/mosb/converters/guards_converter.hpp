// GUARDS-based grid benchmarks (spec/families/games.md): an octile map becomes a directed
// 8-connected graph with objectives `length` (10 / 14) and `exposure` (guards seeing the cells).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/converters/movingai.hpp"
#include "mosb/graph_builder.hpp"

namespace mosb::converters {

struct Guard {
  std::uint32_t x = 0, y = 0;
  // Radius in thousandths of a cell (the file allows at most 3 decimals); nullopt: unlimited.
  std::optional<std::uint64_t> radius_milli;
  std::uint64_t line = 0;
};

// `x y [radius]` per line, `#` starts a comment; a guard outside the map or on a blocked cell is an
// error naming its line.
std::vector<Guard> parse_guards(std::string_view text, const std::string& display_name,
                                const OctileMap& map);

// Exposure grid: `height` lines of `width` whitespace-separated values, non-negative integers on
// passable cells, any token on blocked cells (stored as 0). Row-major, like OctileMap::passable.
std::vector<std::uint64_t> parse_exposure(std::string_view text, const std::string& display_name,
                                          const OctileMap& map);

// Whether the segment between the centres of the two cells touches no blocked cell, each cell a
// closed unit square (the supercover of the segment). Both cells must lie in the map.
bool line_of_sight(const OctileMap& map, std::uint32_t x0, std::uint32_t y0, std::uint32_t x1,
                   std::uint32_t y1);

// Per cell, the number of guards within radius that have line of sight to it (0 on blocked cells).
std::vector<std::uint64_t> compute_exposure(const OctileMap& map, const std::vector<Guard>& guards);

// The grid in the parse_exposure format, one row per line.
std::string format_exposure(const OctileMap& map, const std::vector<std::uint64_t>& exposure);

// The graph alone: vertices are the passable cells in row-major order; vertex data `cell` (x, y).
StreamedGraph build_guards_graph(const OctileMap& map, const std::vector<std::uint64_t>& exposure);

struct GuardsOptions {
  std::string map_file;
  std::optional<std::string> exposure_file;  // exactly one of exposure_file and guards_file
  std::optional<std::string> guards_file;
  std::optional<std::string> scen_file;
  TerrainRules terrain;
  std::optional<std::string> name;  // benchmark; default: the map's base name without ".map"
};

struct GuardsResult {
  StreamedGraph graph;
  OctileMap map;
  std::vector<std::uint64_t> exposure;
};

// Reads the inputs (decompressing as needed) and builds the instance; throws mosb::Error.
GuardsResult convert_guards(const GuardsOptions& options);

}  // namespace mosb::converters
