// The paper's random-cost Grid family (spec/GENERATORS.md).
#pragma once

#include <cstdint>

#include "mosb/graph_builder.hpp"

namespace mosb::converters {

struct GridParameters {
  std::uint32_t width = 0;   // K columns
  std::uint32_t height = 0;  // M rows
  std::uint32_t objectives = 2;
  std::uint64_t seed = 1;
  std::uint32_t min_cost = 1;
  std::uint32_t max_cost = 10;
};

// Vertices: cell (x, y) is y*K + x; the source is K*M, the target K*M + 1. The arcs come out in
// tail order, so the instance streams into its file (write_graph) without an arc list in memory.
StreamedGraph grid_graph(const GridParameters& p);

// The same instance held in memory.
GraphInput generate_grid(const GridParameters& p);

}  // namespace mosb::converters
