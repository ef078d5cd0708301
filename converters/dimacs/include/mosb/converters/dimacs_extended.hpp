// DIMACS-Extended road networks (spec/families/road.md): objectives derived from a converted DIMACS
// graph (elevation difference, average out-degree of the end vertices, hop count) and benchmark
// views over the columns of one instance.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/converters/dimacs_converter.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/enum_names.hpp"
#include "mosb/graph_builder.hpp"
#include "mosb/views.hpp"  // ViewSpec, add_views: the views of every family

namespace mosb::converters {

// How the average out-degree (an integer or half-integer) is stored as an integer cost.
enum class AvgOutdegreeMode {
  twice,          // outdeg(u) + outdeg(v): exactly twice the average (the default)
  round_half_up,  // floor((outdeg(u) + outdeg(v) + 1) / 2)
};
inline constexpr auto kAvgOutdegreeModeNames = enum_names<AvgOutdegreeMode>({
    {AvgOutdegreeMode::twice, "twice"},
    {AvgOutdegreeMode::round_half_up, "round-half-up"},
});

struct ExtendedOptions {
  std::optional<std::string> elevation_file;
  bool avg_outdegree = false;
  AvgOutdegreeMode avg_outdegree_mode = AvgOutdegreeMode::twice;
  bool hop = false;
  std::vector<ViewSpec> views;
};

// Parses an elevation file: `c` comments, one `p aux sp elev n` line, then one `v id elevation`
// line (signed integer) per vertex. Errors are "FILE:LINE:COLUMN: message".
std::vector<std::int64_t> parse_dimacs_elevation(std::string_view text,
                                                 const std::string& display_name, unsigned id_base,
                                                 std::uint64_t vertex_count);
std::vector<std::int64_t> parse_dimacs_elevation(text::TextSource& source,
                                                 const std::string& display_name, unsigned id_base,
                                                 std::uint64_t vertex_count);

// Out-degree of every vertex in the directed graph as read (parallel arcs and loops counted).
std::vector<std::uint32_t> out_degrees(std::uint64_t vertex_count,
                                       const std::vector<std::uint32_t>& tails);

// Cost columns in the fixed order elevation, avg_outdegree, hop, appended after the existing ones.
void append_derived_columns(GraphInput& graph, const ExtendedOptions& options, unsigned id_base);

// `mosb convert dimacs` as a whole: convert_dimacs, then the derived columns, then the views; out
// of memory names the first .gr file. The one code path of the command and of the suite's recipes.
GraphInput convert_dimacs_extended(const DimacsOptions& options, const ExtendedOptions& extended);

}  // namespace mosb::converters
