// What a figure shows, read from instances and solution files: the data of mosb/report/plots.hpp's
// figures, computed here once for both `mosb plot` and `mosb report`, so that the program (and any
// other caller) only opens files and writes documents. Titles are the caller's.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/graph_reader.hpp"
#include "mosb/report/plots.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/stats.hpp"

namespace mosb::plots {

// The Pearson matrix of `stats` (spec/STATS.md): its objectives' names, 1 on the diagonal and
// each pair's ρ (nullopt, drawn "n/a", where undefined).
CorrelationPlot correlation_of(const ArcGroupStats& stats);

// Vertices per out-degree of `instance`.
DegreePlot degrees_of(const GraphReader& instance);

// The unit of objective `objective` (metadata objective.NAME.unit), empty when none is given.
std::string objective_unit(const GraphReader& instance, std::string_view objective);

// The map of a grid instance (metadata map.width/map.height, vertex data `cell` (x, y); the games
// family, spec/families/games.md §2), drawn with MapSquares of at most `max_side` squares per
// side: each passable cell shaded by the cost of an orthogonal move into it in objective
// `exposure_objective` (and that objective's unit) when the instance has one, and the guards of
// metadata map.guards. `instance` must be verified in full (its cells and CSR are walked). Throws
// mosb::Error naming the file when it is not a grid or its map does not fit it: map.width or
// map.height not a whole number from 1 to 2^32 - 1, a map of more than 2^32 - 2 cells or of fewer
// cells than the instance has vertices (each checked before anything of the map's size is
// allocated), vertex data 'cell' not one (x, y) pair per vertex, a vertex outside the map or two
// on one cell, map.guards malformed. Time and memory: O(vertices + arcs + max_side²), whatever
// the map's size.
MapPlot map_of(const GraphReader& instance, std::string_view exposure_objective,
               std::uint32_t max_side);

// The cells of a metadata value map.guards, "x,y;x,y;..." (spec/families/games.md §5), each on a
// width x height map; throws mosb::Error "NAME: metadata map.guards: ..." when malformed.
std::vector<Point2> parse_guard_cells(std::string_view text, std::uint32_t width,
                                      std::uint32_t height, const std::string& name);

// Adds the paths of query `query`'s front in `solutions` (bound to `instance`, verified) to `map`
// (map_of's), as sequences of its squares. Throws when the file holds no paths, the query is not
// solved, or a path vertex is not one of the instance's.
void add_front_paths(MapPlot& map, const GraphReader& instance, const SolutionReader& solutions,
                     std::uint64_t query);

// Adds the start and goal squares of the given queries of set `query_set` (positions past its end
// are skipped) to `map` (map_of's) as markers. Throws as map_of when `instance` is not a grid.
void add_query_markers(MapPlot& map, const GraphReader& instance, std::string_view query_set,
                       std::span<const std::uint64_t> queries);

// The vectors of query `query`'s front in `solutions` (a position below its query count), one row
// of its objectives' values each, in file order. Throws mosb::Error (invalid_argument), giving the
// query's status, when the query is not solved.
std::vector<std::vector<double>> front_rows(const SolutionReader& solutions, std::uint64_t query);

// Each row's values of objectives x and y: a front's projection on two of its objectives.
std::vector<Point2> pair_points(const std::vector<std::vector<double>>& rows, std::size_t x,
                                std::size_t y);

// A front figure's axes, what `plot front` and the report's front figures share: objectives x and
// y of `solutions` by name, with their units when `instance` (the instance the file is bound to)
// is not null, and the file's objective count (a projection of more says so).
FrontPlot front_axes(const SolutionReader& solutions, const GraphReader* instance, std::size_t x,
                     std::size_t y);

// `mosb plot front` (spec/EVALUATION.md §5): query `query`'s front in `solutions` on objectives x
// and y, labelled with their names, and `reference`'s front under it when not null
// (check_same_binding holds between the two); the labels carry the objectives' units when
// `instance` (the instance the files are bound to) is not null. Each set is named by its file's
// solver (else "solver", and "reference"). Throws as front_rows, for `solutions` first.
FrontPlot front_of(const SolutionReader& solutions, const SolutionReader* reference,
                   const GraphReader* instance, std::uint64_t query, std::size_t x, std::size_t y);

// The front size of every solved query of `solutions`; the other queries are counted as left out.
CardinalityPlot cardinality_of(const SolutionReader& solutions);

}  // namespace mosb::plots
