#include <CLI/CLI.hpp>
#include <memory>

#include "graph_output.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/converters/suite.hpp"

namespace mosb::cli {

namespace {

struct GridArgs {
  converters::GridParameters params;
  GraphOutput output;
  std::string suite;
  std::vector<std::uint32_t> sizes = converters::paper_grid_sizes();
  unsigned threads = 0;
  bool pack = false;
};

int run_grid(const GridArgs& a) {
  if (!a.suite.empty()) {
    TerminalProgress progress;
    const auto entries =
        converters::run_suite(a.suite, converters::grid_suite(a.params.seed, a.sizes),
                              {a.threads, progress.callback(), suite_pack(a.pack)});
    return report_suite(a.suite, "Grid", entries, a.output.json);
  }
  if (a.output.file.empty()) throw UsageError("--output FILE is required (or --suite DIR)");
  // Streamed: memory holds the reverse CSR only, not the arc list (BENCHMARKS.md).
  return write_converted(a.output, {},
                         [&](const Progress&) { return converters::grid_graph(a.params); });
}

}  // namespace

Command add_generate_grid(CLI::App& generate) {
  auto* grid =
      generate.add_subcommand("grid", "The paper's random-cost 4-connected grid (Grid family)");
  auto args = std::make_shared<GridArgs>();
  auto& p = args->params;
  p.width = 300;
  p.height = 300;
  p.objectives = 3;
  auto* width = grid->add_option("--width", p.width, "K, the number of columns")
                    ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
                    ->check(CLI::Range(1u, 60000u))
                    ->capture_default_str();
  auto* height = grid->add_option("--height", p.height, "M, the number of rows")
                     ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
                     ->check(CLI::Range(1u, 60000u))
                     ->capture_default_str();
  auto* objectives = grid->add_option("--objectives", p.objectives, "number of cost columns")
                         ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
                         ->check(CLI::Range(1u, 16u))
                         ->capture_default_str();
  add_seed_option(grid, p.seed, "seed of the specified generator (with --suite: of the suite)");
  add_graph_output_options(grid, args->output);
  auto* directory = grid->add_option(
      "--suite", args->suite,
      "write the paper's 49 Grid graphs (3 objectives) and a MANIFEST into this directory");
  auto* sizes = grid->add_option("--sizes", args->sizes,
                                 "with --suite: only grids of these comma-separated widths and "
                                 "heights, each pair (a small suite; default: the paper's 300, "
                                 "350, ..., 600)")
                    ->delimiter(',')
                    ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
                    ->check(CLI::Range(1u, 60000u));
  // Hidden: the worker count (tests).
  auto* threads = grid->add_option("--threads", args->threads, "suite worker threads")
                      ->check(unsigned_integer(std::numeric_limits<unsigned>::max()))
                      ->group("");
  for (auto* single_only : {width, height, objectives, grid->get_option("--output"),
                            grid->get_option("--expect-digest"), grid->get_option("--view")})
    directory->excludes(single_only);
  sizes->needs(directory);
  threads->needs(directory);
  add_suite_pack_flag(grid, args->pack)->needs(directory);
  return {grid, [args] { return run_grid(*args); }};
}

}  // namespace mosb::cli
