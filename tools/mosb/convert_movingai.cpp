#include <CLI/CLI.hpp>
#include <memory>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/converters/movingai.hpp"
#include "mosb/graph_builder.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct MovingaiArgs {
  std::string map;
  std::string scen;
  TerrainOptions terrain;
  std::string name;
  std::string output;
  std::string expect_digest;
  std::vector<std::string> views;
  bool json = false;
};

int run_movingai(const MovingaiArgs& a) {
  check_output_is_not_input(a.output, {a.map, a.scen});
  converters::MovingaiOptions o;
  o.map_file = a.map;
  if (!a.scen.empty()) o.scen_file = a.scen;
  o.terrain = a.terrain.rules();
  if (!a.name.empty()) o.name = a.name;
  TerminalProgress progress;
  write_graph(with_views(converters::convert_movingai(o), a.views), a.output, progress.callback(),
              a.expect_digest);
  return report_written(a.output, a.json);
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
  add_output_option(movingai, args->output, "the .mosb file to write")->required();
  add_view_spec_option(movingai, args->views);
  add_expect_digest_option(movingai, args->expect_digest);
  add_json_flag(movingai, args->json);
  return {movingai, [args] { return run_movingai(*args); }};
}

}  // namespace mosb::cli
