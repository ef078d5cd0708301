#include <CLI/CLI.hpp>
#include <memory>

#include "graph_output.hpp"
#include "mosb/converters/movingai.hpp"

namespace mosb::cli {

namespace {

struct MovingaiArgs {
  std::string map;
  std::string scen;
  TerrainOptions terrain;
  std::string name;
  GraphOutput output;
};

int run_movingai(const MovingaiArgs& a) {
  converters::MovingaiOptions o;
  o.map_file = a.map;
  if (!a.scen.empty()) o.scen_file = a.scen;
  o.terrain = a.terrain.rules();
  if (!a.name.empty()) o.name = a.name;
  return write_converted(a.output, {a.map, a.scen},
                         [&](const Progress&) { return converters::convert_movingai(o); });
}

}  // namespace

Command add_convert_movingai(CLI::App& convert) {
  auto* movingai = convert.add_subcommand(
      "movingai", "Moving AI octile map (8-connected, no corner cutting): objective length");
  auto args = std::make_shared<MovingaiArgs>();
  movingai->add_option("--map", args->map, "the octile .map file")
      ->required()
      ->check(CLI::ExistingFile);
  movingai->add_option("--scen", args->scen, "a Moving AI scenario, imported as query set 'scen'")
      ->check(CLI::ExistingFile);
  add_terrain_options(movingai, args->terrain);
  movingai->add_option("--name", args->name,
                       "benchmark name (default: the map's base name without .map)");
  add_graph_output_options(movingai, args->output)->required();
  return {movingai, [args] { return run_movingai(*args); }};
}

}  // namespace mosb::cli
