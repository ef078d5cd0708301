// What the example solvers share: the command line, the graph as spans, the per-objective
// backward Dijkstra heuristic and the output. The graph is read in place from the mapping: the
// solvers see spans into it and never copy the CSR or a cost column.
#pragma once

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <queue>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/graph_reader.hpp"

namespace examples {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// One objective's arc costs in whatever type the file stores them; solvers read a value as double
// (exact for integer costs and path sums below 2^53).
struct CostColumn {
  const void* data = nullptr;
  double (*read)(const void*, std::size_t) = nullptr;
  double operator[](std::size_t arc) const { return read(data, arc); }
};

template <class T>
double read_as_double(const void* data, std::size_t arc) {
  return static_cast<double>(static_cast<const T*>(data)[arc]);
}

template <class T>
CostColumn column_of(std::span<const T> values) {
  return {values.data(), &read_as_double<T>};
}

struct Graph {
  std::size_t vertex_count = 0;
  std::span<const std::uint64_t> offsets, reverse_offsets;
  std::span<const std::uint32_t> targets, reverse_sources, reverse_arcs;
  std::vector<CostColumn> costs;  // the chosen objectives, in order
};

struct Options {
  std::string program, instance, view, query_set, fronts_dir;
  std::vector<std::string> objectives;  // --objectives: names overriding the view's list
  std::vector<mosb::Query> queries;     // --query S T ...
  bool protocol = false;                // --protocol: speak mosb run's solver protocol
};

// An instance ready to solve; `owner` keeps whatever the spans point into alive.
struct Instance {
  Graph graph;
  std::vector<mosb::Query> queries;
  std::shared_ptr<const void> owner;
};

using Front = std::vector<std::vector<double>>;

[[noreturn]] inline void usage_error(const std::string& program, const std::string& message) {
  std::fprintf(stderr,
               "%s: %s\nusage: %s INSTANCE [--view V] [--objectives A,B,...] "
               "[--queries SET | --query S T ...] [--fronts DIR] "
               "[--protocol]\n",
               program.c_str(), message.c_str(), program.c_str());
  std::exit(2);
}

inline std::uint32_t parse_vertex(const Options& o, const char* text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text, &end, 10);
  if (*text < '0' || *text > '9' || *end != '\0' || errno != 0 || v > mosb::format::kMaxCount)
    usage_error(o.program, std::string("'") + text + "' is not a vertex id");
  return static_cast<std::uint32_t>(v);
}

inline Options parse_args(int argc, char** argv) {
  Options o;
  o.program = std::filesystem::path(argv[0]).filename().string();
  auto value = [&](int& i) -> std::string {
    if (i + 1 >= argc) usage_error(o.program, std::string(argv[i]) + " needs a value");
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--view") {
      o.view = value(i);
    } else if (arg == "--queries") {
      o.query_set = value(i);
    } else if (arg == "--fronts") {
      o.fronts_dir = value(i);
    } else if (arg == "--protocol") {
      o.protocol = true;
    } else if (arg == "--objectives") {
      const std::string list = value(i);
      for (std::size_t pos = 0; pos <= list.size();) {
        const std::size_t comma = std::min(list.find(',', pos), list.size());
        o.objectives.push_back(list.substr(pos, comma - pos));
        pos = comma + 1;
      }
    } else if (arg == "--query") {
      if (i + 2 >= argc) usage_error(o.program, "--query needs a start and a goal");
      const std::uint32_t s = parse_vertex(o, argv[i + 1]);
      o.queries.push_back({s, parse_vertex(o, argv[i + 2])});
      i += 2;
    } else if (arg.starts_with("-") && arg != "-") {
      usage_error(o.program, "unknown option '" + arg + "'");
    } else if (o.instance.empty()) {
      o.instance = arg;
    } else {
      usage_error(o.program, "more than one instance given");
    }
  }
  if (o.instance.empty()) usage_error(o.program, "no instance given");
  if (!o.query_set.empty() && !o.queries.empty())
    usage_error(o.program, "--queries and --query exclude each other");
  if (o.protocol && (o.queries.size() != 1 || !o.fronts_dir.empty()))
    usage_error(o.program, "--protocol needs exactly one --query S T and no --fronts");
  return o;
}

// The objectives and queries a .mosb run uses. View: --view, else the file's only view, else the
// first in name order; a file without views uses all its objectives. Queries: --query, else
// --queries, else the view's query set, else the file's only query set.
// The structure is verified first (one pass over the file): the search indexes by ids from it.
inline Instance open_mosb(const Options& o) {
  auto reader = std::make_shared<const mosb::GraphReader>(
      mosb::GraphReader::open(o.instance, mosb::VerifyLevel::structure));
  const mosb::GraphReader& r = *reader;
  const std::string file = r.display_name();
  std::optional<mosb::View> view;
  if (!o.view.empty()) {
    view = r.view(o.view);
  } else if (auto names = r.view_names(); !names.empty()) {
    view = r.view(*std::min_element(names.begin(), names.end()));
  }
  std::vector<std::size_t> objectives;
  if (!o.objectives.empty()) {
    for (const auto& name : o.objectives) objectives.push_back(r.objective_index(name));
  } else if (view) {
    objectives = view->objectives;
  } else {
    for (std::size_t i = 0; i < r.objective_count(); ++i) objectives.push_back(i);
  }
  if (objectives.empty()) throw mosb::Error(file + ": no objective to optimize");

  Instance in;
  in.queries = o.queries;
  if (in.queries.empty()) {
    std::string set = o.query_set;
    if (set.empty() && view) set = view->query_set;
    if (set.empty()) {
      auto sets = r.all(mosb::format::SectionKind::queries);
      if (sets.size() != 1)
        throw mosb::Error(file + ": " +
                          (view ? "view '" + view->name + "' names no query set" : "no view") +
                          " and the file has " + std::to_string(sets.size()) +
                          " query sets; choose one with --queries or give --query S T");
      set = sets.front()->name;
    }
    auto stored = r.queries(set);
    in.queries.assign(stored.begin(), stored.end());
  }
  for (const auto& q : in.queries)
    if (q.start >= r.vertex_count() || q.goal >= r.vertex_count())
      throw mosb::Error(file + ": query " + std::to_string(q.start) + " " + std::to_string(q.goal) +
                        " names a vertex beyond the " + std::to_string(r.vertex_count()) +
                        " vertices");

  Graph& g = in.graph;
  g.vertex_count = r.vertex_count();
  g.offsets = r.forward_offsets();
  g.targets = r.forward_targets();
  g.reverse_offsets = r.reverse_offsets();
  g.reverse_sources = r.reverse_sources();
  g.reverse_arcs = r.reverse_arcs();
  for (std::size_t i : objectives)
    g.costs.push_back(r.visit_cost(i, [](auto values) { return column_of(values); }));
  in.owner = reader;
  return in;
}

// Exact distance from every vertex to `goal` under one objective, on the reverse CSR: a consistent
// heuristic for the forward search (infinity where the goal is unreachable).
inline std::vector<double> distances_to(const Graph& g, std::uint32_t goal,
                                        const CostColumn& cost) {
  std::vector<double> dist(g.vertex_count, kInfinity);
  using Entry = std::pair<double, std::uint32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  dist[goal] = 0;
  open.push({0, goal});
  while (!open.empty()) {
    const auto [d, v] = open.top();
    open.pop();
    if (d > dist[v]) continue;
    for (std::uint64_t e = g.reverse_offsets[v]; e < g.reverse_offsets[v + 1]; ++e) {
      const std::uint32_t u = g.reverse_sources[e];
      const double nd = d + cost[g.reverse_arcs[e]];
      if (nd < dist[u]) {
        dist[u] = nd;
        open.push({nd, u});
      }
    }
  }
  return dist;
}

// Writes DIR/<index>.txt atomically (mosb::write_file_atomically): one cost vector per line,
// values separated by one space, lines sorted lexicographically by value (examples/README.md).
inline void write_front(const std::string& dir, std::size_t index, Front front) {
  std::sort(front.begin(), front.end());
  std::string text;
  char number[32];
  for (const auto& costs : front) {
    for (std::size_t k = 0; k < costs.size(); ++k) {
      std::snprintf(number, sizeof number, "%.17g", costs[k]);
      text += (k ? " " : "") + std::string(number);
    }
    text += '\n';
  }
  mosb::write_file_atomically(std::filesystem::path(dir) / (std::to_string(index) + ".txt"), text);
}

// The solver protocol of `mosb run` (spec/RUN.md): the front on stdout, one vector per line in
// the shortest %.17g form, lines sorted as in front files; the statistics on stderr.
inline void print_protocol(Front front, double seconds, std::uint64_t expansions) {
  std::sort(front.begin(), front.end());
  char number[32];
  for (const auto& costs : front) {
    for (std::size_t k = 0; k < costs.size(); ++k) {
      std::snprintf(number, sizeof number, "%.17g", costs[k]);
      std::fputs(k ? " " : "", stdout);
      std::fputs(number, stdout);
    }
    std::fputc('\n', stdout);
  }
  std::fflush(stdout);
  std::fprintf(stderr, "mosb: expanded=%llu\nmosb: runtime_seconds=%.6f\n",
               static_cast<unsigned long long>(expansions), seconds);
}

// The whole program around a solver: Front solve(const Graph&, Query, uint64_t& expansions).
template <class Open, class Solve>
int run(int argc, char** argv, Open open, Solve solve, std::size_t needed_objectives = 0) {
  const Options o = parse_args(argc, argv);
  try {
    const Instance in = open(o);
    if (needed_objectives && in.graph.costs.size() != needed_objectives)
      usage_error(o.program, o.instance + ": " + std::to_string(in.graph.costs.size()) +
                                 " objectives chosen, this solver needs " +
                                 std::to_string(needed_objectives) +
                                 " (pick them with --objectives)");
    if (!o.fronts_dir.empty()) std::filesystem::create_directories(o.fronts_dir);
    for (std::size_t i = 0; i < in.queries.size(); ++i) {
      const auto started = std::chrono::steady_clock::now();
      std::uint64_t expansions = 0;
      Front front = solve(in.graph, in.queries[i], expansions);
      const std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;
      if (o.protocol) {
        print_protocol(std::move(front), took.count(), expansions);
        continue;
      }
      std::printf("%u %u %zu %.6f %llu\n", in.queries[i].start, in.queries[i].goal, front.size(),
                  took.count(), static_cast<unsigned long long>(expansions));
      std::fflush(stdout);
      if (!o.fronts_dir.empty()) write_front(o.fronts_dir, i, std::move(front));
    }
  } catch (const mosb::Error& e) {
    std::fprintf(stderr, "%s: %s\n", o.program.c_str(), e.what());
    return 1;
  } catch (const std::exception& e) {  // filesystem and allocation failures
    std::fprintf(stderr, "%s: %s: %s\n", o.program.c_str(), o.instance.c_str(), e.what());
    return 1;
  }
  return 0;
}

}  // namespace examples
