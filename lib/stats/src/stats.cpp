#include "mosb/stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <type_traits>

#include "mosb/error.hpp"

namespace mosb {

namespace {

using format::ElementType;

// Arcs are streamed in blocks so that the centred values of every objective fit in cache.
constexpr std::size_t kBlock = 2048;
constexpr std::size_t kKindGroups = 256;

[[noreturn]] void fail(const GraphReader& graph, const std::string& what) {
  throw Error(graph.display_name() + ": " + what);
}

// Per (group, objective): count, range and mean, from one pass over the column.
struct Moments {
  std::uint64_t count = 0;
  long double min = 0, max = 0, mean = 0;
};

// Sums integers exactly in 128 bits (two u64 words): m < 2^32 values below 2^64 cannot overflow.
struct ExactSum {
  std::uint64_t low = 0, high = 0;
  void add(std::uint64_t v) {
    low += v;
    if (low < v) ++high;
  }
  long double value() const { return std::ldexp(static_cast<long double>(high), 64) + low; }
};

template <class T>
void first_pass(std::span<const T> column, std::span<const std::uint8_t> kind, std::size_t groups,
                std::size_t objective, std::size_t objective_count, std::vector<Moments>& out) {
  std::vector<T> lo(groups, std::numeric_limits<T>::max());
  std::vector<T> hi(groups, std::numeric_limits<T>::lowest());
  std::vector<std::uint64_t> count(groups, 0);
  using Sum = std::conditional_t<std::is_integral_v<T>, ExactSum, long double>;
  std::vector<Sum> sum(groups);
  for (std::size_t a = 0; a < column.size(); ++a) {
    const std::size_t g = kind.empty() ? 0 : kind[a];
    const T v = column[a];
    if (v < lo[g]) lo[g] = v;
    if (v > hi[g]) hi[g] = v;
    ++count[g];
    if constexpr (std::is_integral_v<T>)
      sum[g].add(v);
    else
      sum[g] += v;
  }
  for (std::size_t g = 0; g < groups; ++g) {
    auto& m = out[g * objective_count + objective];
    m.count = count[g];
    if (count[g] == 0) continue;
    m.min = lo[g];
    m.max = hi[g];
    long double total;
    if constexpr (std::is_integral_v<T>)
      total = sum[g].value();
    else
      total = sum[g];
    m.mean = total / static_cast<long double>(count[g]);
  }
}

// Both passes over the arcs for `groups` groups (1, or 256 keyed by `kind`).
std::vector<ArcGroupStats> grouped_stats(const GraphReader& graph,
                                         const std::vector<std::size_t>& objectives,
                                         std::span<const std::uint8_t> kind, std::size_t groups) {
  const std::size_t d = objectives.size();
  const std::size_t m = graph.arc_count();
  std::vector<Moments> moments(groups * d);
  for (std::size_t i = 0; i < d; ++i)
    graph.visit_cost(objectives[i],
                     [&](auto column) { first_pass(column, kind, groups, i, d, moments); });

  // Co-moments Σ (x − mean_x)(y − mean_y) per group, for every i ≤ j (the diagonal gives
  // variances).
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t i = 0; i < d; ++i)
    for (std::size_t j = i; j < d; ++j) pairs.emplace_back(i, j);
  std::vector<long double> co(groups * pairs.size(), 0.0L);
  std::vector<long double> centred(d * kBlock);
  for (std::size_t start = 0; start < m; start += kBlock) {
    const std::size_t length = std::min(kBlock, m - start);
    for (std::size_t i = 0; i < d; ++i)
      graph.visit_cost(objectives[i], [&](auto column) {
        long double* c = centred.data() + i * kBlock;
        for (std::size_t k = 0; k < length; ++k) {
          const std::size_t g = kind.empty() ? 0 : kind[start + k];
          c[k] = static_cast<long double>(column[start + k]) - moments[g * d + i].mean;
        }
      });
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const long double* x = centred.data() + pairs[p].first * kBlock;
      const long double* y = centred.data() + pairs[p].second * kBlock;
      if (kind.empty()) {
        long double s = 0;
        for (std::size_t k = 0; k < length; ++k) s += x[k] * y[k];
        co[p] += s;
      } else {
        for (std::size_t k = 0; k < length; ++k)
          co[kind[start + k] * pairs.size() + p] += x[k] * y[k];
      }
    }
  }

  std::vector<ArcGroupStats> result(groups);
  auto diagonal = [&](std::size_t g, std::size_t i) {
    const std::size_t p = i * d - i * (i - 1) / 2;  // position of (i, i) in `pairs`
    return co[g * pairs.size() + p];
  };
  for (std::size_t g = 0; g < groups; ++g) {
    auto& r = result[g];
    r.arc_count = d == 0 ? (kind.empty() ? m : 0) : moments[g * d].count;
    for (std::size_t i = 0; i < d; ++i) {
      const auto& s = graph.objective(objectives[i]);
      const auto& mo = moments[g * d + i];
      ObjectiveStats o{s.name, s.type, {}, {}, {}};
      if (mo.count > 0) {
        o.min = mo.min;
        o.mean = mo.mean;
        o.max = mo.max;
      }
      r.objectives.push_back(std::move(o));
    }
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      const auto [i, j] = pairs[p];
      if (i == j) continue;
      Correlation c{i, j, std::nullopt};
      const auto& mi = moments[g * d + i];
      const auto& mj = moments[g * d + j];
      const long double vi = diagonal(g, i), vj = diagonal(g, j);
      // A constant column (min = max, decided exactly) has no defined correlation.
      if (mi.count >= 2 && mi.min != mi.max && mj.min != mj.max && vi > 0 && vj > 0) {
        const long double rho = co[g * pairs.size() + p] / std::sqrt(vi * vj);
        c.rho = static_cast<double>(std::clamp(rho, -1.0L, 1.0L));
      }
      r.correlations.push_back(c);
    }
  }
  return result;
}

std::span<const std::uint8_t> kind_column(const GraphReader& graph) {
  const Section* s = graph.find(format::SectionKind::arc_data, "kind");
  if (!s)
    throw Error(ErrorCode::other,
                {graph.display_name() + ": no arc data section 'kind' (needed by ",
                 setting("by_kind"), ")"});
  if (s->type != ElementType::u8 || s->entry.row_width != 1)
    fail(graph, "arc data section 'kind' holds " + std::string(format::to_string(s->type)) + " x" +
                    std::to_string(s->entry.row_width) + ", not u8 x1");
  const auto values = graph.values<std::uint8_t>(*s);
  if (values.size() != graph.arc_count())
    fail(graph, "arc data section 'kind' has " + std::to_string(values.size()) + " rows for " +
                    std::to_string(graph.arc_count()) + " arcs");
  return values;
}

// Degrees from a CSR offsets column of a verified reader (offsets non-decreasing from 0 to m).
DegreeStats degrees(const GraphReader& graph, std::span<const std::uint64_t> offsets) {
  const std::uint64_t n = graph.vertex_count(), m = graph.arc_count();
  DegreeStats d;
  if (n == 0) return d;
  std::uint64_t lo = std::numeric_limits<std::uint64_t>::max(), hi = 0;
  for (std::uint64_t v = 0; v < n; ++v) {
    const std::uint64_t degree = offsets[v + 1] - offsets[v];
    lo = std::min(lo, degree);
    hi = std::max(hi, degree);
  }
  d.min = lo;
  d.max = hi;
  d.mean = static_cast<double>(static_cast<long double>(m) / static_cast<long double>(n));
  return d;
}

// Every walk below indexes by stored offsets and targets: they run only on a reader whose payload
// passed the checksum and structure checks (GraphReader::open(path, VerifyLevel::full)).
void require_verified(const GraphReader& graph, std::string_view function) {
  graph.require_verified(VerifyLevel::full, function);
}

}  // namespace

ArcMultiplicity count_loops_and_parallel_arcs(const GraphReader& graph) {
  require_verified(graph, "count_loops_and_parallel_arcs");
  ArcMultiplicity stats;
  const auto offsets = graph.forward_offsets();
  const auto targets = graph.forward_targets();
  const auto n = static_cast<std::uint32_t>(graph.vertex_count());
  constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> last_tail(n, kNone);  // the last tail seen with an arc to each head
  for (std::uint32_t u = 0; u < n; ++u)
    for (std::uint64_t a = offsets[u]; a < offsets[u + 1]; ++a) {
      const std::uint32_t v = targets[a];
      if (v == u) ++stats.self_loops;
      if (last_tail[v] == u)
        ++stats.parallel_arcs;
      else
        last_tail[v] = u;
    }
  return stats;
}

ArcGroupStats objective_stats(const GraphReader& graph,
                              const std::vector<std::size_t>& objectives) {
  require_verified(graph, "objective_stats");
  return std::move(grouped_stats(graph, objectives, {}, 1).front());
}

std::vector<KindGroupStats> objective_stats_by_kind(const GraphReader& graph,
                                                    const std::vector<std::size_t>& objectives) {
  require_verified(graph, "objective_stats_by_kind");
  const auto kind = kind_column(graph);
  std::vector<std::uint64_t> count(kKindGroups, 0);
  for (auto k : kind) ++count[k];
  auto groups = grouped_stats(graph, objectives, kind, kKindGroups);
  std::vector<KindGroupStats> result;
  for (std::size_t g = 0; g < kKindGroups; ++g)
    if (count[g] > 0) {
      groups[g].arc_count = count[g];
      result.push_back({static_cast<std::uint8_t>(g), std::move(groups[g])});
    }
  return result;
}

// Iterative Tarjan over the forward CSR: an explicit stack of (vertex, next arc) replaces
// recursion.
SccSummary strongly_connected_components(const GraphReader& graph) {
  require_verified(graph, "strongly_connected_components");
  const auto offsets = graph.forward_offsets();
  const auto targets = graph.forward_targets();
  const auto n = static_cast<std::uint32_t>(graph.vertex_count());
  constexpr std::uint32_t kUnvisited = std::numeric_limits<std::uint32_t>::max();  // n ≤ 2^32 − 2
  std::vector<std::uint32_t> index(n, kUnvisited), low(n, 0);
  std::vector<bool> on_stack(n, false);
  std::vector<std::uint32_t> component_stack;
  std::vector<std::pair<std::uint32_t, std::uint64_t>> calls;
  std::uint32_t next_index = 0;
  SccSummary summary;
  auto visit = [&](std::uint32_t v) {
    index[v] = low[v] = next_index++;
    component_stack.push_back(v);
    on_stack[v] = true;
    calls.emplace_back(v, offsets[v]);
  };
  for (std::uint32_t root = 0; root < n; ++root) {
    if (index[root] != kUnvisited) continue;
    visit(root);
    while (!calls.empty()) {
      const std::uint32_t v = calls.back().first;
      if (calls.back().second < offsets[v + 1]) {
        const std::uint32_t w = targets[calls.back().second++];
        if (index[w] == kUnvisited)
          visit(w);
        else if (on_stack[w])
          low[v] = std::min(low[v], index[w]);
        continue;
      }
      calls.pop_back();
      if (!calls.empty()) {
        const std::uint32_t parent = calls.back().first;
        low[parent] = std::min(low[parent], low[v]);
      }
      if (low[v] != index[v]) continue;
      std::uint64_t size = 0;
      std::uint32_t w;
      do {
        w = component_stack.back();
        component_stack.pop_back();
        on_stack[w] = false;
        ++size;
      } while (w != v);
      ++summary.count;
      summary.largest = std::max(summary.largest, size);
    }
  }
  return summary;
}

GraphStats compute_stats(const GraphReader& graph, const StatsOptions& options) {
  require_verified(graph, "compute_stats");
  std::vector<std::size_t> objectives;
  if (const auto selected = select_view(graph, options.selection)) {
    objectives = selected->objectives;
  } else {
    for (std::size_t i = 0; i < graph.objective_count(); ++i) objectives.push_back(i);
  }

  GraphStats stats;
  stats.vertex_count = graph.vertex_count();
  stats.arc_count = graph.arc_count();
  stats.out_degree = degrees(graph, graph.forward_offsets());
  stats.in_degree = degrees(graph, graph.reverse_offsets());
  const auto multiplicity = count_loops_and_parallel_arcs(graph);
  stats.self_loops = multiplicity.self_loops;
  stats.parallel_arcs = multiplicity.parallel_arcs;
  const auto scc = strongly_connected_components(graph);
  stats.scc_count = scc.count;
  stats.largest_scc = scc.largest;
  stats.all_arcs = objective_stats(graph, objectives);
  if (options.by_kind) stats.by_kind = objective_stats_by_kind(graph, objectives);
  return stats;
}

}  // namespace mosb
