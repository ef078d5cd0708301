#include "mosb/converters/netmaker_generator.hpp"

#include <algorithm>
#include <array>
#include <memory>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mosb/converters/dimacs_converter.hpp"
#include "mosb/error.hpp"
#include "mosb/random.hpp"

namespace mosb::converters {

namespace {

// Stream indices of the seed (spec/GENERATORS.md, NetMaker).
enum Stream : std::uint64_t {
  permutation = 0,
  degrees = 1,
  locality_choice = 2,
  cycle_costs = 3,
  locality_costs = 4,
  query_pairs = 5
};

void check(const NetMakerParameters& p) {
  if (p.vertices < 2) throw Error("netmaker needs at least 2 vertices");
  if (p.amax <= p.amin)
    throw Error("netmaker amax must exceed amin (out-degrees are drawn from {amin+1..amax})");
  if (std::uint64_t{p.vertices} * p.amax >= 0xFFFFFFFFULL)
    throw Error("netmaker of " + std::to_string(p.vertices) + " vertices with amax " +
                std::to_string(p.amax) + " may exceed 2^32 - 1 arcs");
  if (p.query_percent < 1 || p.query_percent > 50)
    throw Error("netmaker query percent must be 1 to 50");
}

// The candidates of u: the window [lo, hi] in increasing id order without u and its cycle
// successor. Read by index without materializing the window, so a huge I costs nothing.
class Candidates {
 public:
  Candidates(std::uint64_t lo, std::uint64_t hi, std::uint64_t u, std::uint64_t successor)
      : lo_(lo) {
    excluded_[0] = u;
    excluded_count_ = 1;
    if (successor >= lo && successor <= hi) excluded_[excluded_count_++] = successor;
    if (excluded_count_ == 2 && excluded_[1] < excluded_[0]) std::swap(excluded_[0], excluded_[1]);
    count_ = hi - lo + 1 - excluded_count_;
  }
  std::uint64_t count() const { return count_; }
  std::uint64_t at(std::uint64_t index) const {
    std::uint64_t v = lo_ + index;
    for (std::size_t e = 0; e < excluded_count_; ++e)
      if (v >= excluded_[e]) ++v;
    return v;
  }

 private:
  std::uint64_t lo_;
  std::array<std::uint64_t, 2> excluded_{};
  std::size_t excluded_count_ = 0;
  std::uint64_t count_ = 0;
};

// The arcs of a NetMaker graph in tail order, replayable: each pass draws the degree and locality
// streams again, so no arc list is held; only the cycle successor of each vertex (4 bytes).
struct NetMakerArcs {
  NetMakerParameters p;
  std::vector<std::uint32_t> successor;

  // f(tail, head, kind) per arc: per vertex in id order, its cycle arc, then its locality arcs in
  // the order they are drawn.
  template <class F>
  void for_each(F&& f) const {
    const std::uint64_t n = p.vertices;
    const std::uint64_t half = p.locality / 2;
    auto degree = stream(p.seed, Stream::degrees);
    auto choice = stream(p.seed, Stream::locality_choice);
    std::unordered_map<std::uint64_t, std::uint64_t> swapped;  // sparse partial Fisher-Yates
    for (std::uint64_t u = 0; u < n; ++u) {
      f(static_cast<std::uint32_t>(u), successor[u], kNetMakerCycleArc);
      const std::uint64_t wanted = degree.uniform(p.amin + 1, p.amax) - 1;
      const Candidates candidates(u >= half ? u - half : 0, std::min(n - 1, u + half), u,
                                  successor[u]);
      const std::uint64_t taken = std::min(wanted, candidates.count());
      swapped.clear();
      auto value = [&](std::uint64_t index) {
        auto it = swapped.find(index);
        return it == swapped.end() ? candidates.at(index) : it->second;
      };
      for (std::uint64_t i = 0; i < taken; ++i) {
        const std::uint64_t j = choice.uniform(i, candidates.count() - 1);
        const std::uint64_t picked = value(j);
        swapped[j] = value(i);
        f(static_cast<std::uint32_t>(u), static_cast<std::uint32_t>(picked), kNetMakerLocalityArc);
      }
    }
  }
};

}  // namespace

StreamedGraph netmaker_graph(const NetMakerParameters& p) {
  check(p);
  const std::uint64_t n = p.vertices;
  auto arcs = std::make_shared<NetMakerArcs>();
  arcs->p = p;

  // The Hamiltonian cycle: Fisher-Yates over the identity, then sigma[i] -> sigma[i+1 mod n].
  {
    std::vector<std::uint32_t> sigma(n);
    for (std::uint64_t i = 0; i < n; ++i) sigma[i] = static_cast<std::uint32_t>(i);
    auto perm = stream(p.seed, Stream::permutation);
    for (std::uint64_t i = n - 1; i >= 1; --i) std::swap(sigma[i], sigma[perm.uniform(0, i)]);
    arcs->successor.resize(n);
    for (std::uint64_t i = 0; i < n; ++i) arcs->successor[sigma[i]] = sigma[(i + 1) % n];
  }

  StreamedGraph g;
  g.vertex_count = n;
  // The arc kinds (1 byte per arc) are kept: the cost streams follow them.
  auto kind = std::make_shared<std::vector<std::uint8_t>>();
  arcs->for_each([&](std::uint32_t, std::uint32_t, std::uint8_t k) { kind->push_back(k); });
  g.arc_count = kind->size();
  g.replay_arcs = [arcs](const StreamedGraph::ArcSink& sink) {
    arcs->for_each([&](std::uint32_t tail, std::uint32_t head, std::uint8_t) { sink(tail, head); });
  };
  // Cycle arcs draw one value from each third of [1, 1000] and shuffle them over the objectives;
  // locality arcs draw each objective from [1, 99]. Objective j replays both streams, keeping v[j].
  for (std::size_t j = 0; j < 3; ++j)
    g.costs.push_back({"c" + std::to_string(j + 1), "",
                       [seed = p.seed, kind, j](const StreamedGraph::CostSink& sink) {
                         auto cycle_rng = stream(seed, Stream::cycle_costs);
                         auto local_rng = stream(seed, Stream::locality_costs);
                         for (const auto k : *kind) {
                           if (k == kNetMakerCycleArc) {
                             std::array<std::uint64_t, 3> v = {cycle_rng.uniform(1, 333),
                                                               cycle_rng.uniform(334, 666),
                                                               cycle_rng.uniform(667, 1000)};
                             for (std::uint64_t i = 2; i >= 1; --i)
                               std::swap(v[i], v[cycle_rng.uniform(0, i)]);
                             sink(v[j]);
                           } else {
                             std::uint64_t value = 0;
                             for (std::size_t i = 0; i < 3; ++i) {
                               const auto drawn = local_rng.uniform(1, 99);
                               if (i == j) value = drawn;
                             }
                             sink(value);
                           }
                         }
                       }});
  g.arc_data.push_back(DataColumn::from("kind", 1, *kind));

  // Distinct pairs: a pair drawn before is drawn again (both endpoints).
  const std::uint64_t band = std::max<std::uint64_t>(1, n * p.query_percent / 100);
  if (band * band < p.queries)
    throw Error("netmaker: " + std::to_string(p.queries) + " distinct queries requested, only " +
                std::to_string(band * band) + " source-target pairs exist");
  auto query_rng = stream(p.seed, Stream::query_pairs);
  std::set<std::pair<std::uint64_t, std::uint64_t>> seen;
  QuerySet queries{"default", {}};
  while (queries.pairs.size() < p.queries) {
    const std::uint64_t s = query_rng.uniform(0, band - 1);
    const std::uint64_t t = query_rng.uniform(n - band, n - 1);
    if (seen.insert({s, t}).second)
      queries.pairs.push_back({static_cast<std::uint32_t>(s), static_cast<std::uint32_t>(t)});
  }
  g.queries.push_back(std::move(queries));

  auto& md = g.metadata;
  md.set("benchmark",
         p.name ? *p.name : "NetMaker-N" + std::to_string(n) + "-I" + std::to_string(p.locality));
  md.set("family", "synthetic");
  md.set("id_base", "0");
  md.set("source.command", "generate netmaker");
  md.set("source.param.vertices", std::to_string(n));
  md.set("source.param.amin", std::to_string(p.amin));
  md.set("source.param.amax", std::to_string(p.amax));
  md.set("source.param.locality", std::to_string(p.locality));
  md.set("source.param.seed", std::to_string(p.seed));
  md.set("source.param.queries", std::to_string(p.queries));
  md.set("source.param.query_percent", std::to_string(p.query_percent));
  if (p.name) md.set("source.param.name", *p.name);
  md.set("view." + netmaker_view(n, 3) + ".objectives", "c1,c2,c3");
  md.set("view." + netmaker_view(n, 3) + ".queries", "default");
  return g;
}

std::string netmaker_view(std::uint64_t vertices, std::size_t objectives) {
  return "NetMaker-" +
         (vertices % 1000 == 0 && vertices > 0 ? std::to_string(vertices / 1000) + "k"
                                               : std::to_string(vertices)) +
         "_" + std::to_string(objectives);
}

GraphInput generate_netmaker(const NetMakerParameters& p) {
  return materialize(netmaker_graph(p));
}

GraphInput convert_netmaker(const std::filesystem::path& gr_file,
                            const std::optional<std::string>& name) {
  DimacsOptions options;
  options.gr_files = {gr_file.string()};
  options.id_base = 0;
  options.name = name;
  GraphInput g = convert_dimacs(options);
  if (g.costs.empty())
    throw Error(gr_file.string() + ": a NetMaker graph needs at least one cost column");
  auto& md = g.metadata;
  md.set("family", "synthetic");
  md.set("source.command", "convert netmaker");
  std::string objectives;
  for (std::size_t j = 1; j <= g.costs.size(); ++j)
    objectives += (j > 1 ? ",c" : "c") + std::to_string(j);
  md.set("view." + netmaker_view(g.vertex_count, g.costs.size()) + ".objectives", objectives);
  return g;
}

}  // namespace mosb::converters
