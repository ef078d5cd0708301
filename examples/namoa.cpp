// d-objective label-setting search in the style of NAMOA*dr / LTMOA* (Pulido et al. 2015;
// Hernández et al. 2023): labels leave the open list in lexicographic order of f = g + h, with h
// the exact backward distance per objective; so a label's first cost is never below that of any
// earlier label at its vertex, and dominance is checked on the remaining d - 1 objectives only
// (dimensionality reduction), against the expanded labels of the vertex and the solutions found.
//
// Built twice: `namoa` reads a .mosb mapping in place; `namoa_text` (EXAMPLES_TEXT_LOADER, the
// benchmark's baseline) loads DIMACS .gr text into vectors first, as solvers commonly do.
#include <algorithm>
#include <cstdint>
#include <queue>
#include <vector>

#include "example_common.hpp"
#ifdef EXAMPLES_TEXT_LOADER
#include "text_loader.hpp"
#endif

namespace {

using examples::Front;
using examples::Graph;

// Truncated cost vectors (objectives 2..d) kept mutually non-dominated, flattened. With d = 1
// the width is 0 and any entry dominates: the search is Dijkstra's.
class TruncatedSet {
 public:
  bool weakly_dominates(const double* t, std::size_t width) const {
    for (std::size_t i = 0; i < count_; ++i)
      if (std::equal(t, t + width, values_.begin() + i * width, std::greater_equal<>()))
        return true;
    return false;
  }
  // Adds t (not weakly dominated by the set) and drops the entries t dominates.
  void insert(const double* t, std::size_t width) {
    std::size_t kept = 0;
    for (std::size_t i = 0; i < count_; ++i) {
      auto entry = values_.begin() + i * width;
      if (std::equal(t, t + width, entry, std::less_equal<>())) continue;
      std::copy_n(entry, width, values_.begin() + kept * width);
      ++kept;
    }
    values_.resize(kept * width);
    values_.insert(values_.end(), t, t + width);
    count_ = kept + 1;
  }

 private:
  std::vector<double> values_;
  std::size_t count_ = 0;
};

Front namoa(const Graph& g, mosb::Query q, std::uint64_t& expansions) {
  const std::size_t d = g.costs.size();
  std::vector<std::vector<double>> h;
  for (const auto& cost : g.costs) h.push_back(examples::distances_to(g, q.goal, cost));
  Front front;
  if (h[0][q.start] == examples::kInfinity) return front;

  // Label i: vertex[i], and g then f (2d values) at pool[2d*i].
  std::vector<double> pool;
  std::vector<std::uint32_t> vertex;
  auto g_of = [&](std::size_t i) { return pool.data() + 2 * d * i; };
  auto f_of = [&](std::size_t i) { return pool.data() + 2 * d * i + d; };
  auto later = [&](std::size_t a, std::size_t b) {
    const double *fa = f_of(a), *fb = f_of(b);
    return std::lexicographical_compare(fb, fb + d, fa, fa + d);
  };
  std::priority_queue<std::size_t, std::vector<std::size_t>, decltype(later)> open(later);
  std::vector<TruncatedSet> expanded(g.vertex_count);  // per vertex; at the goal: the solutions
  std::vector<double> child(2 * d);

  auto add_label = [&](std::uint32_t v, const double* costs_and_estimates) {
    vertex.push_back(v);
    pool.insert(pool.end(), costs_and_estimates, costs_and_estimates + 2 * d);
    open.push(vertex.size() - 1);
  };
  for (std::size_t k = 0; k < d; ++k) child[k] = 0, child[d + k] = h[k][q.start];
  add_label(q.start, child.data());

  while (!open.empty()) {
    const std::size_t i = open.top();
    open.pop();
    const std::uint32_t v = vertex[i];
    if (expanded[v].weakly_dominates(g_of(i) + 1, d - 1) ||
        expanded[q.goal].weakly_dominates(f_of(i) + 1, d - 1))
      continue;
    expanded[v].insert(g_of(i) + 1, d - 1);
    ++expansions;
    if (v == q.goal) {
      front.emplace_back(g_of(i), g_of(i) + d);
      continue;
    }
    for (std::uint64_t a = g.offsets[v]; a < g.offsets[v + 1]; ++a) {
      const std::uint32_t w = g.targets[a];
      if (h[0][w] == examples::kInfinity) continue;
      const double* parent = g_of(i);
      for (std::size_t k = 0; k < d; ++k) {
        child[k] = parent[k] + g.costs[k][a];
        child[d + k] = child[k] + h[k][w];
      }
      if (expanded[w].weakly_dominates(child.data() + 1, d - 1) ||
          expanded[q.goal].weakly_dominates(child.data() + d + 1, d - 1))
        continue;
      add_label(w, child.data());
    }
  }
  return front;
}

}  // namespace

int main(int argc, char** argv) {
#ifdef EXAMPLES_TEXT_LOADER
  return examples::run(argc, argv, examples::open_text, namoa);
#else
  return examples::run(argc, argv, examples::open_mosb, namoa);
#endif
}
