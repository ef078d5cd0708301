#include <CLI/CLI.hpp>
#include <memory>

#include "commands.hpp"
#include "mosb/converters/grid_generator.hpp"

namespace mosb::cli {

Command add_generate_grid(CLI::App& generate) {
  auto* grid = generate.add_subcommand("grid", "The paper's random-cost 4-connected grid (Grid family)");
  auto params = std::make_shared<converters::GridParameters>();
  auto output = std::make_shared<std::string>();
  params->width = 300;
  params->height = 300;
  params->objectives = 3;
  grid->add_option("--width", params->width, "K, the number of columns")
      ->check(CLI::Range(1u, 60000u))->capture_default_str();
  grid->add_option("--height", params->height, "M, the number of rows")
      ->check(CLI::Range(1u, 60000u))->capture_default_str();
  grid->add_option("--objectives", params->objectives, "number of cost columns")
      ->check(CLI::Range(1u, 16u))->capture_default_str();
  grid->add_option("--seed", params->seed, "seed of the specified generator")->capture_default_str();
  grid->add_option("-o,--output", *output, "the .mosb file to write")->required();
  return {grid, [params, output] {
            write_graph(converters::generate_grid(*params), *output);
            return report_written(*output);
          }};
}

}  // namespace mosb::cli
