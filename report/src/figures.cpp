#include "mosb/report/figures.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "mosb/error.hpp"

namespace mosb::plots {

namespace {

struct Grid {
  std::uint32_t width = 0, height = 0;
  std::vector<Point2> cell;  // of each vertex, on the map
};

// A metadata value as an error message quotes it: at most 40 bytes.
std::string quoted(const std::string& value) {
  return "'" + (value.size() <= 40 ? value : value.substr(0, 40) + "...") + "'";
}

// Metadata `key` (map.width or map.height): a whole number from 1 to 2^32 - 1, decimal digits
// without a leading zero and nothing else ("5x", "-5", "4294967301" are refused, not read as 5).
std::uint32_t map_side(const GraphReader& reader, const char* key) {
  const std::string text = reader.metadata().get(key).value_or("");
  std::uint64_t value = 0;
  const char* end = text.data() + text.size();
  const bool digits = !text.empty() && text.size() <= 10 && text.front() != '0' &&
                      text.find_first_not_of("0123456789") == std::string::npos;
  if (!digits || std::from_chars(text.data(), end, value).ptr != end || value > UINT32_MAX)
    throw Error(reader.display_name() + ": metadata " + key + " " + quoted(text) +
                " is not a whole number from 1 to 4294967295");
  return static_cast<std::uint32_t>(value);
}

// Refuses a map the instance's vertices cannot be the passable cells of (spec/families/games.md
// §2: one vertex per passable cell, so at most width x height vertices, and a map of at most
// 2^32 - 2 cells, as convert movingai reads one), before anything of its size is allocated.
void check_map_fits(const GraphReader& reader, const Grid& grid, const Section& cells) {
  const std::string& name = reader.display_name();
  const std::uint64_t area = std::uint64_t{grid.width} * grid.height;
  const std::string size = std::to_string(grid.width) + " x " + std::to_string(grid.height) +
                           " map (" + std::to_string(area) + " cells)";
  if (area > format::kMaxCount)
    throw Error(name + ": metadata map.width and map.height give a " + size + ", more than the " +
                std::to_string(format::kMaxCount) + " a map may have");
  if (reader.vertex_count() > area)
    throw Error(name + ": its " + std::to_string(reader.vertex_count()) +
                " vertices do not fit a " + size + ", one vertex per passable cell");
  if (cells.entry.row_width != 2 || cells.element_count() != 2 * reader.vertex_count() ||
      (cells.type != format::ElementType::u16 && cells.type != format::ElementType::u32))
    throw Error(name + ": vertex data 'cell' is not one (x, y) pair of u16 or u32 per vertex");
}

// Refuses two vertices on one cell: the map counts each passable cell once.
void check_distinct_cells(const GraphReader& reader, const Grid& grid) {
  std::vector<std::pair<std::uint64_t, std::size_t>> at;  // (row-major cell, vertex)
  at.reserve(grid.cell.size());
  for (std::size_t v = 0; v < grid.cell.size(); ++v)
    at.emplace_back(static_cast<std::uint64_t>(grid.cell[v].y) * grid.width +
                        static_cast<std::uint64_t>(grid.cell[v].x),
                    v);
  std::sort(at.begin(), at.end());
  for (std::size_t k = 1; k < at.size(); ++k)
    if (at[k].first == at[k - 1].first) {
      const Point2 c = grid.cell[at[k].second];
      throw Error(reader.display_name() + ": vertices " + std::to_string(at[k - 1].second) +
                  " and " + std::to_string(at[k].second) + " lie on the same cell (" +
                  std::to_string(static_cast<std::uint64_t>(c.x)) + ", " +
                  std::to_string(static_cast<std::uint64_t>(c.y)) + ")");
    }
}

// The map's size and each vertex's cell, checked to lie on the map, one vertex per cell.
Grid grid_of(const GraphReader& reader) {
  const auto& meta = reader.metadata();
  const auto* cells = reader.find(format::SectionKind::vertex_data, "cell");
  if (!meta.get("map.width") || !meta.get("map.height") || cells == nullptr)
    throw Error(reader.display_name() +
                ": not a grid instance (needs metadata map.width, map.height and vertex data "
                "'cell')");
  Grid grid;
  grid.width = map_side(reader, "map.width");
  grid.height = map_side(reader, "map.height");
  check_map_fits(reader, grid, *cells);
  grid.cell.resize(reader.vertex_count());
  auto read_cells = [&](auto values) {
    for (std::size_t v = 0; v < grid.cell.size(); ++v) {
      const auto x = values[2 * v], y = values[2 * v + 1];
      if (x >= grid.width || y >= grid.height)
        throw Error(reader.display_name() + ": vertex " + std::to_string(v) + "'s cell (" +
                    std::to_string(x) + ", " + std::to_string(y) + ") lies outside the map");
      grid.cell[v] = {static_cast<double>(x), static_cast<double>(y)};
    }
  };
  if (cells->type == format::ElementType::u16)
    read_cells(reader.values<std::uint16_t>(*cells));
  else
    read_cells(reader.values<std::uint32_t>(*cells));
  check_distinct_cells(reader, grid);
  return grid;
}

// Only a solved query has a front (or paths) to draw; the error gives the query's status.
void require_solved(const SolutionReader& solutions, std::uint64_t query) {
  const auto status = solutions.status(query);
  if (status != QueryStatus::solved)
    throw Error(ErrorCode::invalid_argument,
                solutions.display_name() + ": query " + std::to_string(query) + " is " +
                    std::string(to_string(status)) + ", not solved: no front to draw");
}

}  // namespace

CorrelationPlot correlation_of(const ArcGroupStats& stats) {
  CorrelationPlot plot;
  const std::size_t n = stats.objectives.size();
  for (const auto& o : stats.objectives) plot.names.push_back(o.name);
  plot.rho.assign(n, std::vector<std::optional<double>>(n));
  for (std::size_t i = 0; i < n; ++i) plot.rho[i][i] = 1.0;
  for (const auto& c : stats.correlations)
    plot.rho[c.first][c.second] = plot.rho[c.second][c.first] = c.rho;
  return plot;
}

DegreePlot degrees_of(const GraphReader& instance) {
  DegreePlot plot;
  const auto offsets = instance.forward_offsets();
  for (std::size_t v = 0; v + 1 < offsets.size(); ++v) {
    const auto degree = offsets[v + 1] - offsets[v];
    if (degree >= plot.vertices_by_degree.size()) plot.vertices_by_degree.resize(degree + 1, 0);
    ++plot.vertices_by_degree[degree];
  }
  return plot;
}

std::string objective_unit(const GraphReader& instance, std::string_view objective) {
  return instance.metadata().get("objective." + std::string(objective) + ".unit").value_or("");
}

std::vector<Point2> parse_guard_cells(std::string_view text, std::uint32_t width,
                                      std::uint32_t height, const std::string& name) {
  std::vector<Point2> guards;
  const auto bad = [&](const std::string& why) {
    return Error(name + ": metadata map.guards: " + why);
  };
  std::size_t at = 0;
  while (at <= text.size()) {
    const auto end = std::min(text.find(';', at), text.size());
    const std::string item(text.substr(at, end - at));
    // Two runs of 1 to 9 digits around one comma.
    const auto comma = item.find_first_not_of("0123456789");
    if (comma == 0 || comma > 9 || comma == std::string::npos || item[comma] != ',' ||
        item.size() - comma - 1 < 1 || item.size() - comma - 1 > 9 ||
        item.find_first_not_of("0123456789", comma + 1) != std::string::npos)
      throw bad("'" + item + "' is not x,y");
    const unsigned long x = std::stoul(item.substr(0, comma));
    const unsigned long y = std::stoul(item.substr(comma + 1));
    if (x >= width || y >= height) throw bad("'" + item + "' lies outside the map");
    guards.push_back({static_cast<double>(x), static_cast<double>(y)});
    at = end + 1;
  }
  return guards;
}

MapPlot map_of(const GraphReader& reader, std::string_view exposure_objective,
               std::uint32_t max_side) {
  reader.require_verified(VerifyLevel::full, "a map");
  const Grid grid = grid_of(reader);
  std::vector<Point2> guards;
  if (const auto text = reader.metadata().get("map.guards"))
    guards = parse_guard_cells(*text, grid.width, grid.height, reader.display_name());
  const auto objective = reader.find_objective(exposure_objective);
  MapSquares squares(grid.width, grid.height, max_side, objective.has_value());
  const auto cell = [](const Point2& p) {
    return std::pair{static_cast<std::uint32_t>(p.x), static_cast<std::uint32_t>(p.y)};
  };
  for (const auto& c : grid.cell) squares.add_passable(cell(c).first, cell(c).second);
  if (objective) {
    std::vector<double> cost(reader.arc_count());
    reader.read_cost_as(*objective, cost);
    const auto offsets = reader.forward_offsets();
    const auto targets = reader.forward_targets();
    for (std::size_t u = 0; u + 1 < offsets.size(); ++u)
      for (std::uint64_t a = offsets[u]; a < offsets[u + 1]; ++a) {
        const Point2 from = grid.cell[u], to = grid.cell[targets[a]];
        if (from.x != to.x && from.y != to.y) continue;  // diagonal: charged max of three cells
        squares.add_exposure(cell(to).first, cell(to).second, cost[a]);
      }
  }
  MapPlot plot = squares.plot();
  plot.exposure_unit = objective_unit(reader, exposure_objective);
  for (const auto& g : guards) plot.guards.push_back(square_of(plot, g));
  return plot;
}

void add_front_paths(MapPlot& map, const GraphReader& instance, const SolutionReader& solutions,
                     std::uint64_t query) {
  solutions.check_bound_to(instance);
  const auto& name = solutions.display_name();
  if (!solutions.has_paths())
    throw Error(ErrorCode::invalid_argument,
                name + ": the solver gave no paths (vertex sequences) to draw");
  require_solved(solutions, query);
  const Grid grid = grid_of(instance);
  const std::uint64_t begin = solutions.front_begin(query);
  for (std::uint64_t row = begin; row < begin + solutions.front_size(query); ++row) {
    auto& path = map.paths.emplace_back();
    for (const std::uint32_t v : solutions.path(row)) {
      if (v >= grid.cell.size())
        throw Error(ErrorCode::invalid_argument,
                    name + ": query " + std::to_string(query) + ": path vertex " +
                        std::to_string(v) + " is not a vertex of " + instance.display_name() +
                        "; run mosb solutions verify --instance");
      path.push_back(square_of(map, grid.cell[v]));
    }
  }
}

void add_query_markers(MapPlot& map, const GraphReader& instance, std::string_view query_set,
                       std::span<const std::uint64_t> queries) {
  const Grid grid = grid_of(instance);
  const auto set = instance.queries(query_set);
  for (const auto q : queries)
    if (q < set.size() && set[q].start < grid.cell.size() && set[q].goal < grid.cell.size())
      map.queries.push_back(
          {q, square_of(map, grid.cell[set[q].start]), square_of(map, grid.cell[set[q].goal])});
}

std::vector<std::vector<double>> front_rows(const SolutionReader& solutions, std::uint64_t query) {
  require_solved(solutions, query);
  std::vector<std::vector<double>> rows(solutions.front_size(query));
  const std::uint64_t begin = solutions.front_begin(query);
  for (std::size_t k = 0; k < rows.size(); ++k)
    for (std::size_t i = 0; i < solutions.objective_count(); ++i)
      rows[k].push_back(solutions.value_as_double(i, begin + k));
  return rows;
}

std::vector<Point2> pair_points(const std::vector<std::vector<double>>& rows, std::size_t x,
                                std::size_t y) {
  std::vector<Point2> points;
  points.reserve(rows.size());
  for (const auto& row : rows) points.push_back({row[x], row[y]});
  return points;
}

FrontPlot front_axes(const SolutionReader& solutions, const GraphReader* instance, std::size_t x,
                     std::size_t y) {
  FrontPlot plot;
  plot.x_label = solutions.objective_name(x);
  plot.y_label = solutions.objective_name(y);
  if (instance != nullptr) {
    plot.x_unit = objective_unit(*instance, plot.x_label);
    plot.y_unit = objective_unit(*instance, plot.y_label);
  }
  plot.objective_count = solutions.objective_count();
  return plot;
}

FrontPlot front_of(const SolutionReader& solutions, const SolutionReader* reference,
                   const GraphReader* instance, std::uint64_t query, std::size_t x, std::size_t y) {
  auto plot = front_axes(solutions, instance, x, y);
  plot.solution = pair_points(front_rows(solutions, query), x, y);
  if (const auto name = solutions.solver().name; !name.empty()) plot.solver_name = name;
  if (reference != nullptr) {
    plot.reference = pair_points(front_rows(*reference, query), x, y);
    if (const auto name = reference->solver().name; !name.empty())
      plot.reference_name = "reference " + name;
  }
  return plot;
}

CardinalityPlot cardinality_of(const SolutionReader& solutions) {
  CardinalityPlot plot;
  for (std::uint64_t q = 0; q < solutions.query_count(); ++q) {
    if (solutions.status(q) == QueryStatus::solved)
      plot.sizes.push_back(solutions.front_size(q));
    else
      ++plot.left_out;
  }
  return plot;
}

}  // namespace mosb::plots
