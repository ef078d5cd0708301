#include "commands.hpp"

#include <CLI/CLI.hpp>
#include <iostream>

#include "mosb/graph_reader.hpp"

namespace mosb::cli {

Command group(CLI::App* parent, std::vector<Command> children) {
  parent->require_subcommand(1);
  return {parent, [children = std::move(children)] {
            for (const auto& child : children)
              if (child.subcommand->parsed()) return child.run();
            return 1;
          }};
}

int report_written(const std::string& path) {
  const auto reader = GraphReader::open(path);
  std::cout << "wrote " << path << ": " << reader.vertex_count() << " vertices, "
            << reader.arc_count() << " arcs, " << reader.objective_count() << " objectives, digest "
            << reader.digest() << '\n';
  return 0;
}

Command add_convert(CLI::App& app) {
  auto* convert = app.add_subcommand("convert", "Convert a benchmark from its source format");
  return group(convert, {add_convert_dimacs(*convert), add_convert_netmaker(*convert), add_convert_fmi(*convert), add_convert_guards(*convert), add_convert_movingai(*convert), add_convert_roadmap(*convert)});
}

Command add_generate(CLI::App& app) {
  auto* generate = app.add_subcommand("generate", "Generate a synthetic benchmark instance");
  return group(generate, {add_generate_grid(*generate), add_generate_netmaker(*generate)});
}

}  // namespace mosb::cli
