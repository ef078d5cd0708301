#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/converters/suite.hpp"
#include "mosb/error.hpp"

namespace mosb::cli {

namespace {

struct GridSuiteArgs {
  std::string directory;
  std::vector<std::uint32_t> sizes = converters::paper_grid_sizes();
  unsigned threads = 0;
};

int run_grid_suite(const GridSuiteArgs& a, std::uint64_t seed) {
  const auto entries = converters::run_suite(a.directory, converters::grid_suite(seed, a.sizes),
                                             {a.threads, converters::terminal_progress()});
  std::cout << "wrote " << entries.size() << " Grid instances and MANIFEST to " << a.directory << '\n';
  return 0;
}

}  // namespace

Command add_generate_grid(CLI::App& generate) {
  auto* grid = generate.add_subcommand("grid", "The paper's random-cost 4-connected grid (Grid family)");
  auto params = std::make_shared<converters::GridParameters>();
  auto output = std::make_shared<std::string>();
  auto suite = std::make_shared<GridSuiteArgs>();
  params->width = 300;
  params->height = 300;
  params->objectives = 3;
  auto* width = grid->add_option("--width", params->width, "K, the number of columns")
                    ->check(CLI::Range(1u, 60000u))->capture_default_str();
  auto* height = grid->add_option("--height", params->height, "M, the number of rows")
                     ->check(CLI::Range(1u, 60000u))->capture_default_str();
  auto* objectives = grid->add_option("--objectives", params->objectives, "number of cost columns")
                         ->check(CLI::Range(1u, 16u))->capture_default_str();
  grid->add_option("--seed", params->seed, "seed of the specified generator (with --suite: of the suite)")
      ->capture_default_str();
  auto* out = grid->add_option("-o,--output", *output, "the .mosb file to write");
  auto* directory = grid->add_option("--suite", suite->directory,
                                     "write the paper's 49 Grid graphs (3 objectives) and a MANIFEST into this directory");
  // Hidden: a subset of widths/heights (tests), and the worker count.
  auto* sizes = grid->add_option("--sizes", suite->sizes, "suite widths and heights")
                    ->delimiter(',')->check(CLI::Range(1u, 60000u))->group("");
  auto* threads = grid->add_option("--threads", suite->threads, "suite worker threads")->group("");
  for (auto* single_only : {width, height, objectives, out}) directory->excludes(single_only);
  sizes->needs(directory);
  threads->needs(directory);
  return {grid, [params, output, suite] {
            if (!suite->directory.empty()) return run_grid_suite(*suite, params->seed);
            if (output->empty()) throw Error("generate grid: --output FILE is required (or --suite DIR)");
            write_graph(converters::generate_grid(*params), *output);
            return report_written(*output);
          }};
}

}  // namespace mosb::cli
