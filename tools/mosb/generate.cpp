#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "mosb/converters/grid_generator.hpp"
#include "mosb/graph_reader.hpp"

namespace mosb::cli {

Command add_generate(CLI::App& app) {
  auto* sub = app.add_subcommand("generate", "Generate a synthetic instance");
  sub->require_subcommand(1);
  auto* grid = sub->add_subcommand("grid", "The paper's random-cost 4-connected grid (Grid family)");
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
  return {sub, [params, output] {
            write_graph(converters::generate_grid(*params), *output);
            const auto reader = GraphReader::open(*output);
            std::cout << "wrote " << *output << ": " << reader.vertex_count() << " vertices, "
                      << reader.arc_count() << " arcs, " << reader.objective_count()
                      << " objectives, digest " << reader.digest() << '\n';
            return 0;
          }};
}

}  // namespace mosb::cli
