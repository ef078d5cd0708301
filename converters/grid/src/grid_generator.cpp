#include "mosb/converters/grid_generator.hpp"

#include <string>

#include "mosb/error.hpp"
#include "mosb/random.hpp"

namespace mosb::converters {

StreamedGraph grid_graph(const GridParameters& p) {
  if (p.width < 1 || p.height < 1) throw Error("grid width and height must be at least 1");
  if (p.objectives < 1 || p.objectives > 16) throw Error("grid objectives must be 1 to 16");
  if (p.min_cost > p.max_cost) throw Error("grid minimum cost exceeds the maximum cost");
  const std::uint64_t cells = std::uint64_t{p.width} * p.height;
  if (cells + 2 >= 0xFFFFFFFFULL)
    throw Error("grid of " + std::to_string(cells) + " cells is too large");
  const auto K = p.width, M = p.height;
  const auto source = static_cast<std::uint32_t>(cells), target = source + 1;

  StreamedGraph g;
  g.vertex_count = cells + 2;
  g.arc_count = 2 * (std::uint64_t{K - 1} * M + std::uint64_t{M - 1} * K) + 2ULL * M;
  // Arcs in vertex order; per cell: left, right, up (y-1), down (y+1); the source's arcs last.
  g.replay_arcs = [K, M, source, target](const StreamedGraph::ArcSink& arc) {
    for (std::uint32_t y = 0; y < M; ++y)
      for (std::uint32_t x = 0; x < K; ++x) {
        const auto v = y * K + x;  // below 2^32 - 2: checked above
        if (x > 0) arc(v, v - 1);
        if (x + 1 < K) arc(v, v + 1);
        if (y > 0) arc(v, v - K);
        if (y + 1 < M) arc(v, v + K);
        if (x + 1 == K) arc(v, target);
      }
    for (std::uint32_t y = 0; y < M; ++y) arc(source, y * K);
  };
  // Objective j: the j-th random stream, one draw per arc in arc order.
  for (std::uint32_t j = 0; j < p.objectives; ++j)
    g.costs.push_back({"c" + std::to_string(j + 1), "",
                       [p, j, arcs = g.arc_count](const StreamedGraph::CostSink& cost) {
                         auto rng = stream(p.seed, j);
                         for (std::uint64_t a = 0; a < arcs; ++a)
                           cost(rng.uniform(p.min_cost, p.max_cost));
                       }});
  g.queries.push_back({"default", {{source, target}}});

  const std::string size = std::to_string(K) + "x" + std::to_string(M);
  g.metadata.set("benchmark", "Grid-" + size);
  g.metadata.set("family", "synthetic");
  g.metadata.set("id_base", "0");
  g.metadata.set("source.command", "generate grid");
  g.metadata.set("source.param.width", std::to_string(K));
  g.metadata.set("source.param.height", std::to_string(M));
  g.metadata.set("source.param.objectives", std::to_string(p.objectives));
  g.metadata.set("source.param.seed", std::to_string(p.seed));
  g.metadata.set("source.param.min_cost", std::to_string(p.min_cost));
  g.metadata.set("source.param.max_cost", std::to_string(p.max_cost));
  for (std::uint32_t d = 2; d <= p.objectives && d <= 3; ++d) {
    std::string objectives;
    for (std::uint32_t j = 1; j <= d; ++j) objectives += (j > 1 ? ",c" : "c") + std::to_string(j);
    const std::string view = "view.Grid_" + std::to_string(d);
    g.metadata.set(view + ".objectives", objectives);
    g.metadata.set(view + ".queries", "default");
  }
  return g;
}

GraphInput generate_grid(const GridParameters& p) {
  return materialize(grid_graph(p));
}

}  // namespace mosb::converters
