// Robot motion-planning roadmaps (paper §"Robot Motion-Planning Roadmaps";
// spec/families/robots.md): (a) per-objective DIMACS-like .gr files (0-based ids, fractional costs)
// with an optional vertex
//     file `id q1 .. qdof`, or
// (b) GraphML as written by OMPL's PlannerData (node `coords`, edge `weight`, optional per-link
//     clearances), from which joint-space length and clearance penalties U(d) are computed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/converters/objective.hpp"
#include "mosb/enum_names.hpp"
#include "mosb/graph_builder.hpp"

namespace mosb::converters {

// automatic: aggregate when the GraphML declares clearance keys, none otherwise.
// both: length, the aggregate and every per-link penalty (the Panda-RRG_2 and _8 views in one
// file).
enum class ClearanceMode { automatic, none, aggregate, per_link, both };

inline constexpr auto kClearanceModeNames = enum_names<ClearanceMode>({
    {ClearanceMode::automatic, "auto"},
    {ClearanceMode::none, "none"},
    {ClearanceMode::aggregate, "aggregate"},
    {ClearanceMode::per_link, "per-link"},
    {ClearanceMode::both, "both"},
});

struct RoadmapOptions {
  // Style (a).
  std::vector<std::string> gr_files;
  std::optional<std::string> vertex_file;
  bool vertices_from_ids = false;  // n = max(declared, largest id + 1) instead of an error
  // Style (b).
  std::optional<std::string> graphml_file;
  ClearanceMode clearance = ClearanceMode::automatic;
  double delta = 0.1;   // the safety band of U(d), in the clearances' unit
  bool weight = false;  // also store the edge attribute `weight` as an objective
  // Both.
  std::vector<Objective> objectives;  // empty: the defaults (c1..cd, or length/clearance...)
  std::optional<std::string> name;
  Progress progress;  // stage "read" of a GraphML file: raw bytes parsed so far
};

// The paper's clearance penalty: 0 for d >= delta, (d - delta)^2 / (2 delta) for 0 < d < delta.
double clearance_penalty(double d, double delta);

// A vertex file: one line `id q1 .. qdof` per vertex (blank lines and lines starting with '#'
// skipped); every line has the same number of coordinates.
struct VertexFile {
  std::uint32_t dof = 0;
  std::vector<std::uint64_t> ids;
  std::vector<std::uint64_t> lines;  // 1-based line of each id
  std::vector<double> coords;        // row-major, ids.size() x dof
};
VertexFile parse_vertex_file(std::string_view text, const std::string& display_name);

// Reads (decompressing as needed) and converts; throws mosb::Error.
GraphInput convert_roadmap(const RoadmapOptions& options);

}  // namespace mosb::converters
