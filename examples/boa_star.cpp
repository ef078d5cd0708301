// Bi-objective A* (BOA*, Hernández et al., ICAPS 2020) over two objectives of a mosb instance:
// one label per distinct Pareto-optimal cost vector from start to goal. The graph is read in
// place from the mapping (example_common.hpp); the heuristics are exact backward distances.
#include <cstdint>
#include <queue>
#include <vector>

#include "example_common.hpp"

namespace {

using examples::Front;
using examples::Graph;

struct Label {
  double g1, g2, f1, f2;
  std::uint32_t vertex;
};

// Min-heap on (f1, f2): the label popped first at a vertex has the least first cost there.
struct Later {
  bool operator()(const Label& a, const Label& b) const {
    return a.f1 != b.f1 ? a.f1 > b.f1 : a.f2 > b.f2;
  }
};

Front boa_star(const Graph& g, mosb::Query q, std::uint64_t& expansions) {
  const std::vector<double> h1 = examples::distances_to(g, q.goal, g.costs[0]);
  const std::vector<double> h2 = examples::distances_to(g, q.goal, g.costs[1]);
  Front front;
  if (h1[q.start] == examples::kInfinity) return front;
  // g2_min[v]: the least second cost of a label expanded at v. With labels popped in (f1, f2)
  // order, a later label at v with g2 >= g2_min[v] is weakly dominated, duplicates included.
  std::vector<double> g2_min(g.vertex_count, examples::kInfinity);
  std::priority_queue<Label, std::vector<Label>, Later> open;
  open.push({0, 0, h1[q.start], h2[q.start], q.start});
  while (!open.empty()) {
    const Label l = open.top();
    open.pop();
    if (l.g2 >= g2_min[l.vertex] || l.f2 >= g2_min[q.goal]) continue;
    g2_min[l.vertex] = l.g2;
    ++expansions;
    if (l.vertex == q.goal) {
      front.push_back({l.g1, l.g2});
      continue;
    }
    for (std::uint64_t a = g.offsets[l.vertex]; a < g.offsets[l.vertex + 1]; ++a) {
      const std::uint32_t w = g.targets[a];
      if (h1[w] == examples::kInfinity) continue;
      const double g1 = l.g1 + g.costs[0][a], g2 = l.g2 + g.costs[1][a];
      const double f2 = g2 + h2[w];
      if (g2 >= g2_min[w] || f2 >= g2_min[q.goal]) continue;
      open.push({g1, g2, g1 + h1[w], f2, w});
    }
  }
  return front;
}

}  // namespace

int main(int argc, char** argv) {
  return examples::run(argc, argv, examples::open_mosb, boa_star, 2);
}
