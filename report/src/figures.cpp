#include "mosb/report/figures.hpp"

#include <algorithm>
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

// The map's size and each vertex's cell, checked to lie on the map.
Grid grid_of(const GraphReader& reader) {
  const auto& meta = reader.metadata();
  const auto width = meta.get("map.width"), height = meta.get("map.height");
  const auto* cells = reader.find(format::SectionKind::vertex_data, "cell");
  if (!width || !height || cells == nullptr)
    throw Error(reader.display_name() +
                ": not a grid instance (needs metadata map.width, map.height and vertex data "
                "'cell')");
  Grid grid;
  try {
    grid.width = static_cast<std::uint32_t>(std::stoul(*width));
    grid.height = static_cast<std::uint32_t>(std::stoul(*height));
  } catch (const std::exception&) {
    throw Error(reader.display_name() + ": metadata map.width/map.height is not a number");
  }
  grid.cell.resize(reader.vertex_count());
  auto read_cells = [&](auto values) {
    for (std::size_t v = 0; v < grid.cell.size(); ++v) {
      const auto x = values[2 * v], y = values[2 * v + 1];
      if (x >= grid.width || y >= grid.height)
        throw Error(reader.display_name() + ": vertex " + std::to_string(v) +
                    "'s cell lies outside the map");
      grid.cell[v] = {static_cast<double>(x), static_cast<double>(y)};
    }
  };
  if (cells->type == format::ElementType::u16)
    read_cells(reader.values<std::uint16_t>(*cells));
  else
    read_cells(reader.values<std::uint32_t>(*cells));
  return grid;
}

std::size_t index_of(const Point2& cell, std::uint32_t width) {
  return static_cast<std::size_t>(cell.y) * width + static_cast<std::size_t>(cell.x);
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

MapPlot map_of(const GraphReader& reader, std::string_view exposure_objective) {
  reader.require_verified(VerifyLevel::full, "a map");
  const Grid grid = grid_of(reader);
  MapPlot plot;
  plot.width = grid.width;
  plot.height = grid.height;
  const std::size_t area = std::size_t{plot.width} * plot.height;
  plot.passable.assign(area, false);
  for (const auto& cell : grid.cell) plot.passable[index_of(cell, plot.width)] = true;
  if (const auto guards = reader.metadata().get("map.guards"))
    plot.guards = parse_guard_cells(*guards, grid.width, grid.height, reader.display_name());
  plot.exposure_unit = objective_unit(reader, exposure_objective);
  const auto objective = reader.find_objective(exposure_objective);
  if (!objective) return plot;
  plot.exposure.assign(area, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> cost(reader.arc_count());
  reader.read_cost_as(*objective, cost);
  const auto offsets = reader.forward_offsets();
  const auto targets = reader.forward_targets();
  for (std::size_t u = 0; u + 1 < offsets.size(); ++u)
    for (std::uint64_t a = offsets[u]; a < offsets[u + 1]; ++a) {
      const Point2 from = grid.cell[u], to = grid.cell[targets[a]];
      if (from.x != to.x && from.y != to.y) continue;  // diagonal: charged max of three cells
      plot.exposure[index_of(to, plot.width)] = cost[a];
    }
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
      path.push_back(grid.cell[v]);
    }
  }
}

void add_query_markers(MapPlot& map, const GraphReader& instance, std::string_view query_set,
                       std::span<const std::uint64_t> queries) {
  const Grid grid = grid_of(instance);
  const auto set = instance.queries(query_set);
  for (const auto q : queries)
    if (q < set.size() && set[q].start < grid.cell.size() && set[q].goal < grid.cell.size())
      map.queries.push_back({q, grid.cell[set[q].start], grid.cell[set[q].goal]});
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

FrontPlot front_of(const SolutionReader& solutions, const SolutionReader* reference,
                   const GraphReader* instance, std::uint64_t query, std::size_t x, std::size_t y) {
  FrontPlot plot;
  plot.x_label = solutions.objective_name(x);
  plot.y_label = solutions.objective_name(y);
  if (instance != nullptr) {
    plot.x_unit = objective_unit(*instance, plot.x_label);
    plot.y_unit = objective_unit(*instance, plot.y_label);
  }
  plot.objective_count = solutions.objective_count();
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
