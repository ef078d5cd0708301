#include "mosb/converters/dimacs_extended.hpp"

#include <set>

#include "mosb/converters/text_input.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/error.hpp"
#include "mosb/format.hpp"
#include "mosb/metadata.hpp"
#include "vertex_values.hpp"

namespace mosb::converters {

namespace {

using namespace text;  // the shared primitives of text_scan.hpp

// The index after the inputs the converter already recorded.
std::size_t next_input_index(const Metadata& m) {
  std::size_t i = 0;
  while (m.get("source.input." + std::to_string(i) + ".name")) ++i;
  return i;
}

std::uint64_t absolute_difference(std::int64_t a, std::int64_t b) {
  return a >= b ? static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b)
                : static_cast<std::uint64_t>(b) - static_cast<std::uint64_t>(a);
}

}  // namespace

std::vector<std::int64_t> parse_dimacs_elevation(std::string_view text,
                                                 const std::string& display_name, unsigned id_base,
                                                 std::uint64_t vertex_count) {
  LineScanner lines(text);
  return parse_vertex_values(lines, display_name, id_base, vertex_count, kElevationFile);
}

std::vector<std::int64_t> parse_dimacs_elevation(TextSource& source,
                                                 const std::string& display_name, unsigned id_base,
                                                 std::uint64_t vertex_count) {
  LineScanner lines(source);
  return parse_vertex_values(lines, display_name, id_base, vertex_count, kElevationFile);
}

std::vector<std::uint32_t> out_degrees(std::uint64_t vertex_count,
                                       const std::vector<std::uint32_t>& tails) {
  std::vector<std::uint32_t> degree(vertex_count, 0);
  for (auto t : tails) ++degree[t];  // m <= 2^32 - 2, so no overflow
  return degree;
}

void append_derived_columns(GraphInput& graph, const ExtendedOptions& options, unsigned id_base) {
  const auto m = graph.tails.size();
  auto& meta = graph.metadata;
  if (options.elevation_file) {
    InputFile input(*options.elevation_file);
    record_input(meta, next_input_index(meta), input.facts());
    naming_input_on_out_of_memory(input.display_name(), [&] {
      const auto elevation =
          parse_dimacs_elevation(input, input.display_name(), id_base, graph.vertex_count);
      std::vector<std::uint64_t> cost(m);
      for (std::size_t k = 0; k < m; ++k)
        cost[k] = absolute_difference(elevation[graph.tails[k]], elevation[graph.heads[k]]);
      graph.costs.push_back({"elevation", "", std::move(cost), std::nullopt});
    });
    meta.set("source.param.elevation", input.facts().base_name);
  }
  if (options.avg_outdegree) {
    const auto degree = out_degrees(graph.vertex_count, graph.tails);
    const bool twice = options.avg_outdegree_mode == AvgOutdegreeMode::twice;
    std::vector<std::uint64_t> cost(m);
    for (std::size_t k = 0; k < m; ++k) {
      const std::uint64_t sum = std::uint64_t{degree[graph.tails[k]]} + degree[graph.heads[k]];
      cost[k] = twice ? sum : (sum + 1) / 2;
    }
    graph.costs.push_back({"avg_outdegree", "", std::move(cost), std::nullopt});
    meta.set("source.param.avg_outdegree", kAvgOutdegreeModeNames.name(options.avg_outdegree_mode));
  }
  if (options.hop)
    graph.costs.push_back({"hop", "", std::vector<std::uint64_t>(m, 1), std::nullopt});
  std::string derived;
  if (options.avg_outdegree) derived = "avg-outdegree";
  if (options.hop) derived += derived.empty() ? "hop" : ",hop";
  if (!derived.empty()) meta.set("source.param.derive", derived);
}

GraphInput convert_dimacs_extended(const DimacsOptions& options, const ExtendedOptions& extended) {
  const std::string first = options.gr_files.empty() ? std::string() : options.gr_files.front();
  return naming_input_on_out_of_memory(first, [&] {
    auto graph = convert_dimacs(options);
    append_derived_columns(graph, extended, options.id_base);
    add_views(graph, extended.views);
    return graph;
  });
}

}  // namespace mosb::converters
