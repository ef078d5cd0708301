// What a figure shows, read from instances and solution files: the data of mosb/report/plots.hpp's
// figures, so that the program (and any other caller) only opens files and writes documents.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include "mosb/graph_reader.hpp"
#include "mosb/report/plots.hpp"
#include "mosb/solution_file.hpp"

namespace mosb::plots {

// The map of a grid instance (metadata map.width/map.height, vertex data `cell` (x, y); the games
// family, spec/families/games.md §2), with each cell shaded by the cost of an orthogonal move into
// it in objective `exposure_objective` when the instance has one. `instance` must be verified in
// full (its cells and CSR are walked). Throws mosb::Error naming the file when it is not a grid.
MapPlot map_of(const GraphReader& instance, std::string_view exposure_objective);

// The cells of a metadata value map.guards, "x,y;x,y;..." (spec/families/games.md §5), each on a
// width x height map; throws mosb::Error "NAME: metadata map.guards: ..." when malformed.
std::vector<Point2> parse_guard_cells(std::string_view text, std::uint32_t width,
                                      std::uint32_t height, const std::string& name);

// Adds the paths of query `query`'s front in `solutions` (bound to `instance`, verified) to `map`,
// as cell sequences. Throws when the file holds no paths, the query is not solved, or a path
// vertex is not one of the instance's.
void add_front_paths(MapPlot& map, const GraphReader& instance, const SolutionReader& solutions,
                     std::uint64_t query);

// Adds the start and goal cells of the given queries of set `query_set` (positions past its end
// are skipped) to `map` as markers. Throws as map_of when `instance` is not a grid.
void add_query_markers(MapPlot& map, const GraphReader& instance, std::string_view query_set,
                       std::span<const std::uint64_t> queries);

}  // namespace mosb::plots
