// `mosb plot`: SVG figures (spec/EVALUATION.md §5). The figures are drawn by mosb_report; this
// file only reads the inputs and writes the document.
#include <CLI/CLI.hpp>
#include <cmath>
#include <limits>
#include <memory>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/converters/guards_converter.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/report/plots.hpp"
#include "mosb/stats.hpp"

namespace mosb::cli {

namespace {

struct PlotArgs {
  std::string instance, output, view, title;
};

void add_common(CLI::App* sub, PlotArgs& args) {
  sub->add_option("INSTANCE", args.instance, "a .mosb instance")
      ->required()
      ->check(CLI::ExistingFile);
  add_output_option(sub, args.output, "the SVG file to write")->required();
  sub->add_option("--title", args.title, "the figure's title (default: the benchmark name)");
}

std::string default_title(const GraphReader& reader, const PlotArgs& args, const char* what) {
  if (!args.title.empty()) return args.title;
  return reader.metadata().get("benchmark").value_or(reader.display_name()) + ": " + what;
}

void write_svg(const PlotArgs& args, const std::string& svg) {
  check_output_is_not_input(args.output, {args.instance});
  converters::write_text_atomically(args.output, svg);
}

int run_correlation(const PlotArgs& args) {
  const auto reader = GraphReader::open(args.instance, VerifyLevel::full);
  StatsOptions options;
  if (!args.view.empty()) options.view = args.view;
  const auto stats = compute_stats(reader, options);
  plots::CorrelationPlot plot;
  plot.title = default_title(reader, args, "objective correlation");
  const std::size_t n = stats.all_arcs.objectives.size();
  for (const auto& o : stats.all_arcs.objectives) plot.names.push_back(o.name);
  plot.rho.assign(n, std::vector<std::optional<double>>(n));
  for (std::size_t i = 0; i < n; ++i) plot.rho[i][i] = 1.0;
  for (const auto& c : stats.all_arcs.correlations)
    plot.rho[c.first][c.second] = plot.rho[c.second][c.first] = c.rho;
  write_svg(args, plots::plot_correlation(plot));
  return 0;
}

// The grid of a games instance: metadata map.width/map.height, vertex data `cell` (x, y), and the
// exposure of a cell as the cost of an orthogonal move into it (spec/families/games.md §2).
int run_map(const PlotArgs& args, const std::string& exposure_objective) {
  const auto reader = GraphReader::open(args.instance, VerifyLevel::full);
  const auto& meta = reader.metadata();
  const auto width_text = meta.get("map.width"), height_text = meta.get("map.height");
  const auto* cells = reader.find(format::SectionKind::vertex_data, "cell");
  if (!width_text || !height_text || cells == nullptr)
    throw Error(reader.display_name() +
                ": not a grid instance (needs metadata map.width, map.height and vertex data "
                "'cell')");
  plots::MapPlot plot;
  plot.title = default_title(reader, args, "map");
  try {
    plot.width = static_cast<std::uint32_t>(std::stoul(*width_text));
    plot.height = static_cast<std::uint32_t>(std::stoul(*height_text));
  } catch (const std::exception&) {
    throw Error(reader.display_name() + ": metadata map.width/map.height is not a number");
  }
  const std::size_t area = std::size_t{plot.width} * plot.height;
  plot.passable.assign(area, false);
  std::vector<std::uint32_t> x(reader.vertex_count()), y(reader.vertex_count());
  auto read_cells = [&](auto values) {
    for (std::size_t v = 0; v < x.size(); ++v) {
      x[v] = static_cast<std::uint32_t>(values[2 * v]);
      y[v] = static_cast<std::uint32_t>(values[2 * v + 1]);
      if (x[v] >= plot.width || y[v] >= plot.height)
        throw Error(reader.display_name() + ": vertex " + std::to_string(v) +
                    "'s cell lies outside the map");
      plot.passable[std::size_t{y[v]} * plot.width + x[v]] = true;
    }
  };
  if (cells->type == format::ElementType::u16)
    read_cells(reader.values<std::uint16_t>(*cells));
  else
    read_cells(reader.values<std::uint32_t>(*cells));
  const auto objective = reader.find_objective(exposure_objective);
  if (objective) {
    plot.exposure.assign(area, std::numeric_limits<double>::quiet_NaN());
    std::vector<double> cost(reader.arc_count());
    reader.read_cost_as(*objective, cost);
    const auto offsets = reader.forward_offsets();
    const auto targets = reader.forward_targets();
    for (std::size_t u = 0; u + 1 < offsets.size(); ++u)
      for (std::uint64_t a = offsets[u]; a < offsets[u + 1]; ++a) {
        const std::uint32_t v = targets[a];
        if (x[u] != x[v] && y[u] != y[v]) continue;  // diagonal: charged max of three cells
        plot.exposure[std::size_t{y[v]} * plot.width + x[v]] = cost[a];
      }
  }
  write_svg(args, plots::plot_map(plot));
  return 0;
}

}  // namespace

Command add_plot(CLI::App& app) {
  auto* plot = app.add_subcommand("plot", "Draw a figure as SVG");
  auto correlation_args = std::make_shared<PlotArgs>();
  auto* correlation =
      plot->add_subcommand("correlation", "the objective-correlation matrix as a heat map");
  add_common(correlation, *correlation_args);
  correlation->add_option("--view", correlation_args->view, "only this view's objectives");
  auto map_args = std::make_shared<PlotArgs>();
  auto exposure = std::make_shared<std::string>("exposure");
  auto* map = plot->add_subcommand(
      "map", "a grid instance's map: blocked cells and exposure shading (games family)");
  add_common(map, *map_args);
  map->add_option("--exposure-objective", *exposure, "the objective shaded per cell")
      ->capture_default_str();
  return group(plot,
               {{correlation, [correlation_args] { return run_correlation(*correlation_args); }},
                {map, [map_args, exposure] { return run_map(*map_args, *exposure); }}});
}

}  // namespace mosb::cli
