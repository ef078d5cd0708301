#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "graph_output.hpp"
#include "mosb/converters/roadmap_converter.hpp"
#include "mosb/error.hpp"

namespace mosb::cli {

namespace {

struct RoadmapArgs {
  std::vector<std::string> gr;
  std::string vertices;
  bool vertices_from_ids = false;
  std::string graphml;
  std::string clearance = "auto";
  double delta = 0.1;
  bool weight = false;
  std::vector<std::string> objectives;
  std::string name;
  GraphOutput output;
};

int run_roadmap(const RoadmapArgs& a) {
  std::vector<std::filesystem::path> inputs(a.gr.begin(), a.gr.end());
  inputs.insert(inputs.end(), {a.vertices, a.graphml});
  converters::RoadmapOptions o;
  o.gr_files = a.gr;
  if (!a.vertices.empty()) o.vertex_file = a.vertices;
  o.vertices_from_ids = a.vertices_from_ids;
  if (!a.graphml.empty()) o.graphml_file = a.graphml;
  const auto mode = converters::kClearanceModeNames.parse(a.clearance);
  if (!mode) throw Error("convert roadmap: unknown --clearance '" + a.clearance + "'");
  o.clearance = *mode;
  o.delta = a.delta;
  o.weight = a.weight;
  for (const auto& spec : a.objectives)
    o.objectives.push_back(converters::parse_objective(spec, "convert roadmap"));
  if (!a.name.empty()) o.name = a.name;
  return write_converted(a.output, inputs, [&](const Progress& progress) {
    o.progress = progress;
    auto input = converters::convert_roadmap(o);
    for (const auto& [key, value] : input.metadata.entries())
      if (key.starts_with("warning."))
        std::cerr << "mosb: warning: " << key.substr(8) << ": " << value << '\n';
    return input;
  });
}

}  // namespace

Command add_convert_roadmap(CLI::App& convert) {
  auto* roadmap = convert.add_subcommand(
      "roadmap",
      "Robot motion-planning roadmaps: per-objective .gr files (0-based ids) or OMPL GraphML");
  auto args = std::make_shared<RoadmapArgs>();
  roadmap->add_option("--gr", args->gr, "a .gr file (0-based ids); one per objective in order")
      ->check(CLI::ExistingFile);
  roadmap
      ->add_option("--vertices", args->vertices,
                   "vertex file 'id q1 .. qdof' per line (vertex data 'config')")
      ->check(CLI::ExistingFile);
  roadmap->add_flag("--vertices-from-ids", args->vertices_from_ids,
                    "size the graph from the largest vertex id when it exceeds the declared count");
  roadmap
      ->add_option("--graphml", args->graphml,
                   "a GraphML roadmap (node 'coords', edge 'weight', clearances)")
      ->check(CLI::ExistingFile);
  roadmap
      ->add_option("--clearance", args->clearance,
                   "auto, none, aggregate, per-link or both (GraphML)")
      ->check(CLI::IsMember(converters::kClearanceModeNames.names()))
      ->capture_default_str();
  roadmap->add_option("--delta", args->delta, "safety band of the clearance penalty U(d)")
      ->check(non_negative_real())
      ->capture_default_str();
  roadmap->add_flag("--weight", args->weight,
                    "also store the GraphML edge attribute 'weight' as an objective");
  roadmap->add_option("--objective", args->objectives, "NAME[:UNIT] of each objective, in order");
  roadmap->add_option("--name", args->name, "benchmark name (default: the first file's base name)");
  add_graph_output_options(roadmap, args->output)->required();
  return {roadmap, [args] { return run_roadmap(*args); }};
}

}  // namespace mosb::cli
