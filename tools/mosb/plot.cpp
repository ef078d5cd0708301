// `mosb plot`: SVG figures (spec/EVALUATION.md §5). mosb_report reads each figure's data from the
// inputs (figures.hpp) and draws it (plots.hpp); this file parses the options, opens the inputs
// and writes the document.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <limits>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/eval.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/report/figures.hpp"
#include "mosb/report/plots.hpp"
#include "mosb/report/render.hpp"
#include "mosb/solution_eval.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/stats.hpp"

namespace mosb::cli {

namespace {

// -o's format (by extension) and the printed size of a PDF or PNG.
struct FigureOutput {
  std::string width, height;
  double dpi = 150;
};

void add_figure_options(CLI::App* sub, FigureOutput& f) {
  sub->add_option("--width", f.width,
                  "the PDF's or PNG's width: a number and a unit, in, pt, cm, mm or px (3.5in)");
  sub->add_option("--height", f.height, "its height (either alone keeps the aspect ratio)");
  sub->add_option("--dpi", f.dpi, "a PNG's resolution in dots per inch")
      ->check(CLI::Range(10.0, 2400.0))
      ->capture_default_str();
}

// The figure as -o's extension says: .svg as drawn, .pdf and .png rendered by librsvg and cairo.
void write_figure(const std::string& output, const std::string& svg, const FigureOutput& f) {
  const auto format = plots::image_format_of(output);
  if (!format) throw UsageError("-o " + output + ": write a figure as .svg, .pdf or .png");
  plots::RenderSize size;
  size.dpi = f.dpi;
  const auto length = [](const std::string& option, const std::string& text) {
    try {
      return plots::parse_length(text);
    } catch (const Error& e) {
      throw UsageError(option + ": " + e.what());
    }
  };
  if (!f.width.empty()) size.width_pt = length("--width", f.width);
  if (!f.height.empty()) size.height_pt = length("--height", f.height);
  if (*format == plots::ImageFormat::svg && (size.width_pt || size.height_pt))
    throw UsageError("--width and --height size a .pdf or .png; an SVG keeps its own size");
  write_file_atomically(output, plots::render_svg(svg, *format, size));
}

struct PlotArgs {
  std::string instance, output, title;
  ViewChoice choice;
  FigureOutput figure;
};

void add_common(CLI::App* sub, PlotArgs& args) {
  sub->add_option("INSTANCE", args.instance, "a .mosb instance")
      ->required()
      ->check(CLI::ExistingFile);
  add_output_option(sub, args.output, "the figure to write: .svg, .pdf or .png")->required();
  add_figure_options(sub, args.figure);
  sub->add_option("--title", args.title, "the figure's title (default: the benchmark name)")
      ->check(printable_text());
}

std::string default_title(const GraphReader& reader, const PlotArgs& args, const char* what) {
  if (!args.title.empty()) return args.title;
  return reader.metadata().get("benchmark").value_or(reader.display_name()) + ": " + what;
}

void write_svg(const PlotArgs& args, const std::string& svg) {
  check_output_is_not_input(args.output, {args.instance});
  write_figure(args.output, svg, args.figure);
}

int run_correlation(const PlotArgs& args) {
  const auto reader = GraphReader::open(args.instance, VerifyLevel::full);
  StatsOptions options;
  options.selection = args.choice;
  auto plot = plots::correlation_of(compute_stats(reader, options).all_arcs);
  plot.title = default_title(reader, args, "objective correlation");
  write_svg(args, plots::plot_correlation(plot));
  return 0;
}

// Throws a usage error unless query q exists in r.
void require_query(const SolutionReader& r, std::uint64_t q) {
  if (q >= r.query_count())
    throw UsageError("--query " + std::to_string(q) + ": " + r.display_name() + " has " +
                     std::to_string(r.query_count()) + " queries");
}

struct MapPaths {
  std::string solutions;
  std::optional<std::uint64_t> query;
};

// The grid of a games instance, with one query's front paths when --solutions is given.
int run_map(const PlotArgs& args, const std::string& exposure_objective, const MapPaths& paths) {
  if (paths.solutions.empty() != !paths.query)
    throw UsageError("--solutions and --query go together: the paths of one query's front");
  const auto reader = GraphReader::open(args.instance, VerifyLevel::full);
  // Every input is opened (and verified) before any of it is used.
  std::optional<SolutionReader> solutions;
  if (!paths.solutions.empty()) solutions.emplace(SolutionReader::open_verified(paths.solutions));
  auto plot = plots::map_of(reader, exposure_objective, plots::kMapSideOfPlot);
  plot.title = default_title(reader, args, "map");
  if (solutions) {
    require_query(*solutions, *paths.query);
    plots::add_front_paths(plot, reader, *solutions, *paths.query);
  }
  std::vector<std::filesystem::path> inputs = {args.instance};
  if (!paths.solutions.empty()) inputs.emplace_back(paths.solutions);
  check_output_is_not_input(args.output, inputs);
  write_figure(args.output, plots::plot_map(plot), args.figure);
  return 0;
}

struct FrontArgs {
  std::string solutions, reference, instance, objectives, epsilon, output, title;
  std::uint64_t query = 0;
  FigureOutput figure;
};

// The two objectives to draw: names of the file's objectives or 0-based positions in its view,
// comma-separated; the first two when none are given.
std::pair<std::size_t, std::size_t> chosen_objectives(const SolutionReader& r,
                                                      const std::string& list) {
  if (r.objective_count() < 2)
    throw Error(ErrorCode::invalid_argument,
                r.display_name() + ": a front plot needs two objectives, the view has " +
                    std::to_string(r.objective_count()));
  if (list.empty()) return {0, 1};
  std::vector<std::size_t> picked;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::optional<std::size_t> index;
    for (std::size_t i = 0; i < r.objective_count(); ++i)
      if (r.objective_name(i) == item) index = i;
    if (!index && !item.empty() && item.size() < 10 &&
        std::all_of(item.begin(), item.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
        std::stoul(item) < r.objective_count())
      index = std::stoul(item);
    if (!index) {
      std::string names;
      for (std::size_t i = 0; i < r.objective_count(); ++i)
        names += (i ? ", " : "") + r.objective_name(i);
      throw UsageError("--objectives: '" + item + "' is not an objective of " + r.display_name() +
                       " (" + names + ", or 0.." + std::to_string(r.objective_count() - 1) + ")");
    }
    picked.push_back(*index);
  }
  if (picked.size() != 2 || picked[0] == picked[1])
    throw UsageError("--objectives: give two different objectives, not '" + list + "'");
  return {picked[0], picked[1]};
}

int run_front(const FrontArgs& args) {
  std::optional<Ratio> epsilon;
  if (!args.epsilon.empty()) {
    if (args.reference.empty())
      throw UsageError("--eps draws the reference's ε-boxes: give --reference");
    try {
      epsilon = parse_epsilon(args.epsilon);
    } catch (const Error& e) {
      throw UsageError("--eps: '" + args.epsilon + "': " + e.what());
    }
  }
  const auto solutions = SolutionReader::open_verified(args.solutions);
  std::optional<SolutionReader> reference;
  if (!args.reference.empty()) {
    reference.emplace(SolutionReader::open_verified(args.reference));
    check_same_binding(*reference, solutions);
  }
  const auto axes = chosen_objectives(solutions, args.objectives);
  std::optional<GraphReader> instance;  // for the objectives' units
  if (!args.instance.empty()) {
    instance.emplace(GraphReader::open(args.instance));
    solutions.check_bound_to(*instance);
  }
  require_query(solutions, args.query);
  auto plot = plots::front_of(solutions, reference ? &*reference : nullptr,
                              instance ? &*instance : nullptr, args.query, axes.first, axes.second);
  if (epsilon) plot.epsilon = epsilon->to_double();
  plot.title = !args.title.empty()
                   ? args.title
                   : "query " + std::to_string(args.query) + " of " + solutions.query_set() + ": " +
                         plot.solver_name + (reference ? " vs reference" : "");
  std::vector<std::filesystem::path> inputs = {args.solutions};
  if (reference) inputs.emplace_back(args.reference);
  if (instance) inputs.emplace_back(args.instance);
  check_output_is_not_input(args.output, inputs);
  write_figure(args.output, plots::plot_front(plot), args.figure);
  return 0;
}

struct CardinalityArgs {
  std::string solutions, output, title;
  FigureOutput figure;
};

int run_cardinality(const CardinalityArgs& args) {
  const auto r = SolutionReader::open_verified(args.solutions);
  auto plot = plots::cardinality_of(r);
  const auto solver = r.solver().name;
  plot.title = !args.title.empty() ? args.title
                                   : (solver.empty() ? std::string("fronts") : solver) + " on " +
                                         r.query_set() + ": front size per query";
  check_output_is_not_input(args.output, {args.solutions});
  write_figure(args.output, plots::plot_cardinality(plot), args.figure);
  return 0;
}

}  // namespace

Command add_plot(CLI::App& app) {
  auto* plot = app.add_subcommand("plot", "Draw a figure as SVG, PDF or PNG");
  auto correlation_args = std::make_shared<PlotArgs>();
  auto* correlation =
      plot->add_subcommand("correlation", "the objective-correlation matrix as a heat map");
  add_common(correlation, *correlation_args);
  add_view_choice_options(correlation, correlation_args->choice, "only these objectives");
  auto map_args = std::make_shared<PlotArgs>();
  auto exposure = std::make_shared<std::string>("exposure");
  auto* map = plot->add_subcommand(
      "map", "a grid instance's map: blocked cells and exposure shading (games family)");
  add_common(map, *map_args);
  map->add_option("--exposure-objective", *exposure, "the objective shaded per cell")
      ->capture_default_str();
  auto map_paths = std::make_shared<MapPaths>();
  map->add_option("--solutions", map_paths->solutions,
                  "a solution file with paths: draw one query's paths (with --query)")
      ->check(CLI::ExistingFile);
  map->add_option("--query", map_paths->query, "the query whose front's paths are drawn")
      ->check(unsigned_integer(std::numeric_limits<std::uint64_t>::max()));
  auto front_args = std::make_shared<FrontArgs>();
  auto* front = plot->add_subcommand(
      "front", "one query's front from a solution file on two objectives, against a reference");
  front->add_option("--solutions", front_args->solutions, "the solver's solution file")
      ->required()
      ->check(CLI::ExistingFile);
  front->add_option("--reference", front_args->reference, "a reference solution file to overlay")
      ->check(CLI::ExistingFile);
  front->add_option("--query", front_args->query, "the query (0-based position in the set)")
      ->required()
      ->check(unsigned_integer(std::numeric_limits<std::uint64_t>::max()));
  front
      ->add_option("--instance", front_args->instance,
                   "the instance the files belong to: axis labels with the objectives' units")
      ->check(CLI::ExistingFile);
  front->add_option("--objectives", front_args->objectives,
                    "the two objectives drawn, names or 0-based positions (default: the first "
                    "two)");
  front->add_option("--eps", front_args->epsilon, "draw each reference vector's ε-box")
      ->check(epsilon_value());
  add_output_option(front, front_args->output, "the figure to write: .svg, .pdf or .png")
      ->required();
  add_figure_options(front, front_args->figure);
  front->add_option("--title", front_args->title, "the figure's title")->check(printable_text());
  auto cardinality_args = std::make_shared<CardinalityArgs>();
  auto* cardinality = plot->add_subcommand(
      "cardinality", "front size per solved query of a solution file, sorted (query hardness)");
  cardinality->add_option("--solutions", cardinality_args->solutions, "a solution file")
      ->required()
      ->check(CLI::ExistingFile);
  add_output_option(cardinality, cardinality_args->output,
                    "the figure to write: .svg, .pdf or .png")
      ->required();
  add_figure_options(cardinality, cardinality_args->figure);
  cardinality->add_option("--title", cardinality_args->title, "the figure's title")
      ->check(printable_text());
  return group(
      plot,
      {{correlation, [correlation_args] { return run_correlation(*correlation_args); }},
       {map, [map_args, exposure, map_paths] { return run_map(*map_args, *exposure, *map_paths); }},
       {front, [front_args] { return run_front(*front_args); }},
       {cardinality, [cardinality_args] { return run_cardinality(*cardinality_args); }}});
}

}  // namespace mosb::cli
