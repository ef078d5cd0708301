#include <CLI/CLI.hpp>
#include <memory>

#include "graph_output.hpp"
#include "mosb/converters/fmi_converter.hpp"

namespace mosb::cli {

namespace {

struct FmiArgs {
  std::string file;
  unsigned costs = 0;
  bool ignore_extra_fields = false;
  std::vector<std::string> objectives;
  std::uint32_t bfs_root = 0;
  std::uint64_t bfs_count = 0;
  bool bfs_undirected = false;
  std::string name;
  GraphOutput output;
  CLI::Option* costs_option = nullptr;
  CLI::Option* bfs_option = nullptr;
};

int run_fmi(const FmiArgs& a) {
  converters::FmiOptions o;
  o.file = a.file;
  if (a.costs_option->count() > 0) o.cost_count = a.costs;
  o.ignore_extra_fields = a.ignore_extra_fields;
  for (const auto& spec : a.objectives)
    o.objectives.push_back(converters::parse_objective(spec, "convert fmi"));
  if (a.bfs_option->count() > 0)
    o.extract_bfs = converters::FmiBfs{a.bfs_root, a.bfs_count, a.bfs_undirected};
  if (!a.name.empty()) o.name = a.name;
  return write_converted(a.output, {a.file}, [&](const Progress& progress) {
    o.progress = progress;
    return converters::convert_fmi(o);
  });
}

}  // namespace

Command add_convert_fmi(CLI::App& convert) {
  auto* fmi = convert.add_subcommand(
      "fmi",
      "FMI / OsmGraphCreator text road graphs (GER_10), optionally a BFS-extracted subgraph");
  auto args = std::make_shared<FmiArgs>();
  fmi->add_option("INPUT", args->file, "the FMI text file (plain, gzip, bzip2, xz or zstd)")
      ->required()
      ->check(CLI::ExistingFile);
  args->costs_option = fmi->add_option("--costs", args->costs,
                                       "D cost fields per edge line: 'src trg c1 .. cD' (default: "
                                       "'src trg cost type [maxspeed]')")
                           ->check(unsigned_integer(std::numeric_limits<unsigned>::max()))
                           ->check(CLI::Range(1u, 64u));
  fmi->add_flag("--ignore-extra-fields", args->ignore_extra_fields,
                "with --costs: skip fields after the D costs (the same number on every edge line)")
      ->needs(args->costs_option);
  fmi->add_option("--objective", args->objectives,
                  "NAME[:UNIT] of each cost column, in order (default: the GER_10 names for D = "
                  "10, else c1..cd)");
  args->bfs_option =
      fmi->add_option("--extract-bfs", args->bfs_root,
                      "keep the first --count vertices in BFS order from this vertex (0-based)")
          ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()));
  auto* count =
      fmi->add_option("--count", args->bfs_count, "number of vertices --extract-bfs keeps")
          ->check(unsigned_integer(std::numeric_limits<std::uint64_t>::max()))
          ->check(CLI::Range(std::uint64_t{1}, format::kMaxCount));
  auto* undirected =
      fmi->add_flag("--bfs-undirected", args->bfs_undirected,
                    "let the BFS follow arcs in both directions (default: out-arcs only)");
  args->bfs_option->needs(count);
  count->needs(args->bfs_option);
  undirected->needs(args->bfs_option);
  fmi->add_option("--name", args->name, "benchmark name (default: the file's base name)");
  add_graph_output_options(fmi, args->output)->required();
  return {fmi, [args] { return run_fmi(*args); }};
}

}  // namespace mosb::cli
