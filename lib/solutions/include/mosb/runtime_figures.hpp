// The data of the runtime figures (spec/EVALUATION.md §7): the cactus plot, the Dolan–Moré
// performance profile and the runtime scatter plot, computed once from queries' statuses and
// runtimes, for the report's SVG figures and the Python package's matplotlib ones alike.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "mosb/solution_file.hpp"

namespace mosb {

// One query as a runtime figure reads it: its status and the runtime shown (the RuntimeSource
// the caller chose), absent where the file has none.
struct QueryRun {
  QueryStatus status = QueryStatus::not_run;
  std::optional<double> runtime;
};

struct FigurePoint {
  double x = 0, y = 0;
  bool operator==(const FigurePoint&) const = default;
};

// One solver's cactus series: its solved queries that have a runtime, sorted by it, the k-th
// (from 1) at (k, runtime). A runtime of 0 s (below the clock's resolution: A*pex reports whole
// milliseconds) has no place on the log axis: counted in `zero`, not drawn.
struct CactusSeries {
  std::vector<FigurePoint> points;
  std::uint64_t solved = 0;  // drawn or not
  std::uint64_t zero = 0;
};
CactusSeries cactus_series(std::span<const QueryRun> runs);

// The Dolan–Moré profile. `runs[q][s]` is solver s's run of query q; every row holds `solvers`
// runs (the caller leaves out the queries some solver has no file for). Over the `queries` some
// solver solved with a runtime, per solver the points (τ, fraction of those queries it solved
// within τ times the best solved runtime), τ ascending and distinct, from (1, 0) unless it
// starts there; a runtime below 1e-6 s counts as 1e-6 s, so that 0 s divides. Throws
// std::invalid_argument on a row of another length.
struct PerformanceProfile {
  std::uint64_t queries = 0;
  std::vector<std::vector<FigurePoint>> series;  // per solver
};
PerformanceProfile performance_profile(const std::vector<std::vector<QueryRun>>& runs,
                                       std::size_t solvers);

// Solver a's runtime (x) against b's (y), query by query (a and b of one length; throws
// std::invalid_argument otherwise): a point per query both completed (solved, or the goal shown
// unreachable) with a runtime above 0 s; `query` says which query each point is.
struct RuntimeScatter {
  std::vector<FigurePoint> points;
  std::vector<std::size_t> query;  // per point, its index in a and b
  std::uint64_t one_only = 0;      // completed by one of the two only (or without a runtime)
  std::uint64_t zero = 0;          // both completed, a runtime of 0 s: no place on a log–log plot
};
RuntimeScatter runtime_scatter(std::span<const QueryRun> a, std::span<const QueryRun> b);

}  // namespace mosb
