// Descriptive statistics of an instance (spec/STATS.md): cost ranges, the paper's pairwise Pearson
// correlation ρ_{i,j} over arcs, degrees, strongly connected components, parallel arcs and loops.
// Computed by streaming over the mapped columns; scratch is per vertex or per fixed-size block.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mosb/format.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/views.hpp"

namespace mosb {

struct ObjectiveStats {
  std::string name;
  format::ElementType type = format::ElementType::u32;
  // nullopt over zero arcs. Integer columns give exact min/max; mean is sum / count.
  std::optional<long double> min, mean, max;
};

struct Correlation {
  std::size_t first = 0, second = 0;  // positions in the objective list, first < second
  std::optional<double> rho;          // nullopt: undefined (a constant column, or < 2 arcs)
};

// The objectives' statistics over one set of arcs: all of them, or those of one `kind` value.
struct ArcGroupStats {
  std::uint64_t arc_count = 0;
  std::vector<ObjectiveStats> objectives;
  std::vector<Correlation> correlations;  // every pair (i, j), i < j, in lexicographic order
};

struct DegreeStats {
  std::optional<std::uint64_t> min, max;  // nullopt when there are no vertices
  std::optional<double> mean;
};

struct KindGroupStats {
  std::uint8_t kind = 0;
  ArcGroupStats stats;
};

struct GraphStats {
  std::uint64_t vertex_count = 0, arc_count = 0;
  ArcGroupStats all_arcs;
  std::vector<KindGroupStats> by_kind;  // only kind values that occur, increasing
  DegreeStats out_degree, in_degree;
  std::uint64_t scc_count = 0, largest_scc = 0;
  std::uint64_t self_loops = 0, parallel_arcs = 0;
};

struct StatsOptions {
  // The objectives, in order: a view's, or a list (mosb::select_view); empty: every objective.
  ViewChoice selection;
  bool by_kind = false;  // also group by the u8 arc-data section `kind`
};

// Every function here walks payload and requires a reader opened with
// GraphReader::open(path, VerifyLevel::full); given another, it throws mosb::Error.
// Throws mosb::Error naming the file for an unknown view or objective, a missing or malformed
// `kind` section (with by_kind), or a packed column.
GraphStats compute_stats(const GraphReader& graph, const StatsOptions& options = {});

// Pieces, usable on their own.
ArcGroupStats objective_stats(const GraphReader& graph, const std::vector<std::size_t>& objectives);
std::vector<KindGroupStats> objective_stats_by_kind(const GraphReader& graph,
                                                    const std::vector<std::size_t>& objectives);
struct SccSummary {
  std::uint64_t count = 0, largest = 0;
};
SccSummary strongly_connected_components(const GraphReader& graph);

// Self-loops, and parallel arcs (each extra copy of an earlier (tail, head) of the same tail).
struct ArcMultiplicity {
  std::uint64_t self_loops = 0, parallel_arcs = 0;
};
ArcMultiplicity count_loops_and_parallel_arcs(const GraphReader& graph);

}  // namespace mosb
