#include <CLI/CLI.hpp>
#include <memory>

#include "graph_output.hpp"
#include "mosb/converters/dimacs_converter.hpp"
#include "mosb/converters/dimacs_extended.hpp"
#include "mosb/error.hpp"

namespace mosb::cli {

namespace {

struct DimacsArgs {
  std::vector<std::string> gr;
  std::vector<std::string> objectives;
  std::string co;
  std::string name;
  unsigned id_base = 1;
  std::string cost_type;
  GraphOutput output;
  std::vector<std::string> derive;
  std::string avg_outdegree_mode = "twice";
  std::string elevation;
};

int run_dimacs(const DimacsArgs& a) {
  std::vector<std::filesystem::path> inputs(a.gr.begin(), a.gr.end());
  inputs.insert(inputs.end(), {a.co, a.elevation});
  converters::DimacsOptions o;
  o.gr_files = a.gr;
  for (const auto& spec : a.objectives)
    o.objectives.push_back(converters::parse_objective(spec, "convert dimacs"));
  if (!a.co.empty()) o.co_file = a.co;
  if (!a.name.empty()) o.name = a.name;
  o.id_base = a.id_base;
  if (!a.cost_type.empty()) {
    const auto type = format::parse_element_type(a.cost_type);
    if (!type) throw Error("convert dimacs: unknown --cost-type '" + a.cost_type + "'");
    o.cost_type = *type;
  }
  converters::ExtendedOptions extended;
  if (!a.elevation.empty()) extended.elevation_file = a.elevation;
  for (const auto& d : a.derive) {
    extended.hop |= d == "hop";
    extended.avg_outdegree |= d == "avg-outdegree";
  }
  extended.avg_outdegree_mode =
      *converters::kAvgOutdegreeModeNames.parse(a.avg_outdegree_mode);  // checked by CLI11
  // The views go last in convert_dimacs_extended, after the derived columns they may name.
  for (const auto& v : a.output.views) extended.views.push_back(mosb::parse_view_spec(v));
  auto output = a.output;
  output.views.clear();
  return write_converted(output, inputs, [&](const Progress& progress) {
    o.progress = progress;
    return converters::convert_dimacs_extended(o, extended);
  });
}

}  // namespace

Command add_convert_dimacs(CLI::App& convert) {
  auto* dimacs = convert.add_subcommand(
      "dimacs", "DIMACS shortest-path .gr files (plain, gzip, bzip2, xz or zstd), optional .co");
  auto args = std::make_shared<DimacsArgs>();
  dimacs
      ->add_option("--gr", args->gr,
                   "a .gr file; one per objective in order, or one with several cost columns")
      ->required()
      ->check(CLI::ExistingFile);
  dimacs->add_option("--objective", args->objectives,
                     "NAME[:UNIT] of each cost column, in order (default c1..cd)");
  dimacs->add_option("--co", args->co, "a .co coordinate file (stored as vertex data 'coords')")
      ->check(CLI::ExistingFile);
  dimacs->add_option("--name", args->name, "benchmark name (default: the first file's base name)");
  add_id_base_option(dimacs, args->id_base, "1");
  dimacs->add_option("--cost-type", args->cost_type,
                     "store every cost column as this type (u8..u64, f32, f64)");
  dimacs
      ->add_option("--elevation", args->elevation,
                   "per-vertex elevations ('p aux sp elev n', 'v id elevation'): appends column "
                   "'elevation' = |elev(u) - elev(v)|")
      ->check(CLI::ExistingFile);
  dimacs
      ->add_option(
          "--derive", args->derive,
          "append derived columns: avg-outdegree, hop (order fixed: elevation, avg_outdegree, hop)")
      ->check(CLI::IsMember({"hop", "avg-outdegree"}))
      ->delimiter(',');
  dimacs
      ->add_option(
          "--avg-outdegree-mode", args->avg_outdegree_mode,
          "avg_outdegree as outdeg(u)+outdeg(v) (twice, exact) or their mean rounded half up")
      ->check(CLI::IsMember(converters::kAvgOutdegreeModeNames.names()))
      ->capture_default_str();
  add_graph_output_options(dimacs, args->output)->required();
  return {dimacs, [args] { return run_dimacs(*args); }};
}

}  // namespace mosb::cli
