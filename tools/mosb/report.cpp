// `mosb report`: instances and solution files as one HTML page, and its tables as LaTeX and CSV
// (spec/EVALUATION.md §7). The page is mosb::pages::make_report's; this file opens the inputs
// and writes the outputs.
#include "mosb/report/report.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/experiment.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pack.hpp"
#include "mosb/report/render.hpp"
#include "mosb/solution_file.hpp"

namespace mosb::cli {

namespace {

struct ReportArgs {
  std::vector<std::string> instances, solutions, references;
  std::string queries, epsilons = "0,0.01,0.05,0.1", output, title = "mosb report", latex, csv;
  std::string figures, figure_format = "svg";
  std::size_t max_points = 1000, max_size = 5'000'000;
  std::optional<RuntimeSource> runtime;
  std::string baseline;
  bool pooled = false, signed_rho = false, comparison_by_benchmark = false;
};

std::vector<std::uint64_t> parse_queries(const std::string& list) {
  std::vector<std::uint64_t> out;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (item.empty() || item.size() > 19 ||
        item.find_first_not_of("0123456789") != std::string::npos)
      throw UsageError("--queries: '" + item + "' is not a query number (0-based)");
    out.push_back(std::stoull(item));
  }
  return out;
}

// The outputs, each a file and its content, all rendered before any is written.
using Outputs = std::vector<std::pair<std::filesystem::path, std::string>>;

// The tables as DIR/NAME.EXT.
void add_tables(Outputs& out, const std::string& directory, const pages::Report& r, bool latex) {
  const std::pair<const char*, const tables::Table*> all[] = {{"suite", &r.suite},
                                                              {"solvers", &r.solvers},
                                                              {"instance-space", &r.instance_space},
                                                              {"comparison", &r.comparison},
                                                              {"coverage", &r.coverage},
                                                              {"spread", &r.spread},
                                                              {"epsilon", &r.epsilon_sizes}};
  for (const auto& [name, table] : all) {
    if (table->rows.empty()) continue;
    std::ostringstream text;
    if (latex)
      tables::write_latex(text, *table);
    else
      tables::write_csv(text, *table);
    out.emplace_back(
        std::filesystem::path(directory) / (std::string(name) + (latex ? ".tex" : ".csv")),
        text.str());
  }
}

// Every figure alone as DIR/NN-NAME.EXT (pages::Figure::name), numbered in page order.
void add_figures(Outputs& out, const std::string& directory, const std::string& extension,
                 const pages::Report& r) {
  const auto format = *plots::kImageFormatNames.parse(extension);
  for (std::size_t k = 0; k < r.figures.size(); ++k) {
    char number[32];
    std::snprintf(number, sizeof number, "%02zu-", k + 1);
    out.emplace_back(
        std::filesystem::path(directory) / (number + r.figures[k].name + "." + extension),
        plots::render_svg(r.figures[k].svg, format, {}));
  }
}

// Writes the page, the tables and the figures all or nothing: every output is rendered in memory,
// then write_files_atomically checks every destination, writes each to a temporary and renames
// them only once all are written (so a full disk or an unwritable directory found on the last
// file leaves no half set, which checking first alone could not promise).
void write_outputs(const ReportArgs& args, const pages::Report& result,
                   const std::vector<std::filesystem::path>& inputs) {
  Outputs outputs;
  std::vector<std::filesystem::path> directories;
  if (!args.latex.empty()) add_tables(outputs, args.latex, result, true);
  if (!args.csv.empty()) add_tables(outputs, args.csv, result, false);
  if (!args.figures.empty()) add_figures(outputs, args.figures, args.figure_format, result);
  for (const auto* d : {&args.latex, &args.csv, &args.figures})
    if (!d->empty()) directories.emplace_back(*d);
  outputs.emplace_back(args.output, result.html);
  std::vector<FileContent> files;
  for (const auto& [path, content] : outputs) {
    check_output_is_not_input(path, inputs);
    files.push_back({path, content});
  }
  write_files_atomically(directories, files);
}

int run_report(const ReportArgs& args) {
  pages::ReportOptions options;
  options.title = args.title;
  if (args.max_points == 0) throw UsageError("--max-points: at least 1");
  options.max_points = args.max_points;
  options.max_bytes = args.max_size;
  options.runtime = args.runtime;
  options.baseline = args.baseline;
  options.pooled_figures = args.pooled;
  options.signed_rho = args.signed_rho;
  options.comparison_by_benchmark = args.comparison_by_benchmark;
  if (!args.queries.empty()) options.queries = parse_queries(args.queries);
  options.epsilons = parse_epsilons(args.epsilons);
  for (const auto& e : options.epsilons) options.epsilon_labels.push_back(e.to_decimal(18));
  std::vector<std::filesystem::path> inputs;
  // Every input is opened and checked before anything is written.
  // An experiment's results directory stands for its instances and its cells' files; a
  // directory of references for its .sol files (spec/EXPERIMENT.md §3).
  std::vector<std::filesystem::path> instance_paths, solution_paths, reference_paths;
  for (const auto& path : args.instances) {
    if (!std::filesystem::is_directory(path)) {
      instance_paths.emplace_back(path);
      continue;
    }
    for (auto& p : result_instances(path)) instance_paths.push_back(std::move(p));
    for (auto& [digest, views] : result_views(path)) options.views[digest].merge(views);
    for (auto& p : experiment_result_files(path)) solution_paths.push_back(std::move(p));
  }
  for (const auto& path : args.solutions)
    for (auto& p : experiment_result_files(path)) solution_paths.push_back(std::move(p));
  std::vector<GraphReader> instances;
  for (const auto& path : instance_paths) {
    instances.push_back(load(path, VerifyLevel::full));
    inputs.emplace_back(path);
  }
  for (const auto& source : args.references)
    for (auto& p : reference_files_of(source, instances)) reference_paths.push_back(std::move(p));
  const auto solutions = open_verified_all(solution_paths);
  const auto references = open_verified_all(reference_paths);
  inputs.insert(inputs.end(), solution_paths.begin(), solution_paths.end());
  inputs.insert(inputs.end(), reference_paths.begin(), reference_paths.end());
  const auto result = pages::make_report(instances, solutions, references, options);
  write_outputs(args, result, inputs);
  std::cout << "wrote " << escape_for_terminal(args.output) << " (" << result.html.size()
            << " bytes, " << result.figures.size() << " figures)";
  for (const auto& [what, directory] :
       {std::pair{"LaTeX tables", &args.latex}, std::pair{"CSV tables", &args.csv},
        std::pair{"figures", &args.figures}})
    if (!directory->empty()) std::cout << "; " << what << " in " << escape_for_terminal(*directory);
  std::cout << '\n';
  for (const auto& note : result.notes)
    std::cerr << "mosb: warning: " << escape_for_terminal(note) << '\n';
  return 0;
}

}  // namespace

Command add_report(CLI::App& app) {
  auto args = std::make_shared<ReportArgs>();
  auto* sub = app.add_subcommand(
      "report",
      "Write instances and solvers' solution files as one self-contained HTML page: the suite "
      "table, the instance space, per benchmark its figures and fronts, the solvers' comparison");
  sub->add_option("INSTANCES", args->instances,
                  "the instances (.mosb, packed or not), or an experiment's results directory "
                  "(its instances and every cell's solution file)")
      ->required()
      ->check(CLI::ExistingPath);
  sub->add_option("--solutions", args->solutions,
                  "solvers' solution files, each bound to one of the instances, or results "
                  "directories")
      ->check(CLI::ExistingPath);
  sub->add_option(
         "--reference", args->references,
         "reference solution files (at most one per instance, view and query set), or "
         "directories of them (mosb solutions reference -o DIR), stores or their URLs (the "
         "references of the report's instances)")
      ->check(reference_source());
  sub->add_option("--queries", args->queries,
                  "comma-separated query numbers whose fronts are drawn (default: the smallest, "
                  "median and largest solved front of each benchmark)");
  sub->add_option("--eps", args->epsilons, "comma-separated ε of the ε-coverage (with --reference)")
      ->capture_default_str();
  sub->add_option("--title", args->title, "the page's title")
      ->check(printable_text())
      ->capture_default_str();
  sub->add_option("--max-points", args->max_points,
                  "vectors drawn per front and set, past which it is thinned (extremes kept)")
      ->check(unsigned_integer(1000000))
      ->capture_default_str();
  sub->add_option("--max-size", args->max_size,
                  "the page's largest size in bytes: fronts are thinned further to stay under it")
      ->check(unsigned_integer(std::numeric_limits<std::size_t>::max()))
      ->capture_default_str();
  add_runtime_option(sub, args->runtime);
  sub->add_option("--baseline", args->baseline,
                  "the solver whose runtimes the scatter plots set against each other one's "
                  "(default: the first)");
  sub->add_flag("--pooled", args->pooled,
                "also the cactus plot and performance profile of every benchmark pooled");
  sub->add_flag("--signed-rho", args->signed_rho,
                "the instance space in signed ρ (default: |ρ|, as the paper's figure)");
  sub->add_flag("--comparison-by-benchmark", args->comparison_by_benchmark,
                "the comparison table as the paper prints it: a row per benchmark, each "
                "solver's columns under its name (default: a row per benchmark and solver)");
  add_output_option(sub, args->output, "the HTML file to write")->required();
  sub->add_option("--latex", args->latex,
                  "also write the tables as LaTeX booktabs tabulars into this directory");
  sub->add_option("--csv", args->csv, "also write the tables as CSV into this directory");
  sub->add_option(
      "--figures", args->figures,
      "also write every figure alone into this directory (NN-NAME.svg|pdf|png, the name "
      "saying the figure's kind, benchmark and query: 07-front-grid_2-q3.svg)");
  sub->add_option("--figure-format", args->figure_format, "the format of --figures' files")
      ->check(CLI::IsMember(plots::kImageFormatNames.names()))
      ->capture_default_str();
  return {sub, [args] { return run_report(*args); }};
}

}  // namespace mosb::cli
