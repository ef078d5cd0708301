#include <CLI/CLI.hpp>
#include <memory>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/converters/guards_converter.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_builder.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct GuardsArgs {
  std::string map;
  std::string exposure;
  std::string guards;
  std::string scen;
  std::string write_exposure;
  TerrainOptions terrain;
  std::string name;
  std::string output;
  std::string expect_digest;
  std::vector<std::string> views;
  bool json = false;
};

int run_guards(const GuardsArgs& a) {
  const std::vector<std::filesystem::path> inputs = {a.map, a.exposure, a.guards, a.scen};
  check_output_is_not_input(a.output, inputs);
  check_output_is_not_input(a.write_exposure, inputs);
  converters::GuardsOptions o;
  o.map_file = a.map;
  if (!a.exposure.empty()) o.exposure_file = a.exposure;
  if (!a.guards.empty()) o.guards_file = a.guards;
  if (!a.scen.empty()) o.scen_file = a.scen;
  o.terrain = a.terrain.rules();
  if (!a.name.empty()) o.name = a.name;
  TerminalProgress progress;
  const auto result = converters::convert_guards(o);
  if (!a.write_exposure.empty())
    write_file_atomically(a.write_exposure,
                          converters::format_exposure(result.map, result.exposure));
  write_graph(with_views(result.graph, a.views), a.output, progress.callback(), a.expect_digest);
  return report_written(a.output, a.json);
}

}  // namespace

Command add_convert_guards(CLI::App& convert) {
  auto* guards = convert.add_subcommand(
      "guards",
      "Moving AI octile map with guard exposure (GUARDS benchmarks): objectives length, exposure");
  auto args = std::make_shared<GuardsArgs>();
  guards->add_option("--map", args->map, "the octile .map file")
      ->required()
      ->check(CLI::ExistingFile);
  auto* exposure =
      guards
          ->add_option("--exposure", args->exposure,
                       "per-cell exposure: height lines of width non-negative integers")
          ->check(CLI::ExistingFile);
  auto* guard_file =
      guards
          ->add_option("--guards", args->guards,
                       "guard positions 'x y [radius]' (exposure = guards with line of sight)")
          ->check(CLI::ExistingFile);
  exposure->excludes(guard_file);
  guards->add_option("--scen", args->scen, "a Moving AI scenario, imported as query set 'scen'")
      ->check(CLI::ExistingFile);
  guards->add_option("--write-exposure", args->write_exposure,
                     "also write the exposure grid (--exposure format)");
  add_terrain_options(guards, args->terrain);
  guards->add_option("--name", args->name,
                     "benchmark name (default: the map's base name without .map)");
  add_output_option(guards, args->output, "the .mosb file to write")->required();
  add_view_spec_option(guards, args->views);
  add_expect_digest_option(guards, args->expect_digest);
  add_json_flag(guards, args->json);
  return {guards, [args] {
            if (args->exposure.empty() == args->guards.empty())
              throw UsageError("give exactly one of --exposure FILE and --guards FILE");
            return run_guards(*args);
          }};
}

}  // namespace mosb::cli
