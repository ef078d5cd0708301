#include <CLI/CLI.hpp>
#include <memory>

#include "graph_output.hpp"
#include "mosb/converters/guards_converter.hpp"

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
  GraphOutput output;
};

int run_guards(const GuardsArgs& a) {
  const std::vector<std::filesystem::path> inputs = {a.map, a.exposure, a.guards, a.scen};
  check_output_is_not_input(a.write_exposure, inputs);
  converters::GuardsOptions o;
  o.map_file = a.map;
  if (!a.exposure.empty()) o.exposure_file = a.exposure;
  if (!a.guards.empty()) o.guards_file = a.guards;
  if (!a.scen.empty()) o.scen_file = a.scen;
  o.terrain = a.terrain.rules();
  if (!a.name.empty()) o.name = a.name;
  return write_converted(a.output, inputs, [&](const Progress&) {
    auto result = converters::convert_guards(o);
    if (!a.write_exposure.empty())
      write_file_atomically(a.write_exposure,
                            converters::format_exposure(result.map, result.exposure));
    return std::move(result.graph);
  });
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
  add_graph_output_options(guards, args->output)->required();
  return {guards, [args] {
            if (args->exposure.empty() == args->guards.empty())
              throw UsageError("give exactly one of --exposure FILE and --guards FILE");
            return run_guards(*args);
          }};
}

}  // namespace mosb::cli
