#include "mosb/runtime_figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mosb {

CactusSeries cactus_series(std::span<const QueryRun> runs) {
  std::vector<double> times;
  for (const auto& run : runs)
    if (run.status == QueryStatus::solved && run.runtime) times.push_back(*run.runtime);
  std::sort(times.begin(), times.end());
  CactusSeries series;
  series.solved = times.size();
  series.zero = static_cast<std::uint64_t>(
      std::find_if(times.begin(), times.end(), [](double t) { return t > 0; }) - times.begin());
  for (std::size_t k = series.zero; k < times.size(); ++k)
    series.points.push_back({static_cast<double>(k + 1), times[k]});
  return series;
}

PerformanceProfile performance_profile(const std::vector<std::vector<QueryRun>>& runs,
                                       std::size_t solvers) {
  constexpr double kFloor = 1e-6;
  const auto solved = [](const QueryRun& r) {
    return r.status == QueryStatus::solved && r.runtime;
  };
  PerformanceProfile profile;
  std::vector<std::vector<double>> ratios(solvers);
  for (const auto& row : runs) {
    if (row.size() != solvers)
      throw std::invalid_argument("performance_profile: a query with " +
                                  std::to_string(row.size()) + " runs, not " +
                                  std::to_string(solvers));
    double best = std::numeric_limits<double>::infinity();
    for (const auto& r : row)
      if (solved(r)) best = std::min(best, *r.runtime);
    if (!std::isfinite(best)) continue;
    ++profile.queries;
    for (std::size_t s = 0; s < solvers; ++s)
      if (solved(row[s]))
        ratios[s].push_back(std::max(*row[s].runtime, kFloor) / std::max(best, kFloor));
  }
  for (auto& r : ratios) {
    std::sort(r.begin(), r.end());
    std::vector<FigurePoint> points;
    for (std::size_t k = 0; k < r.size(); ++k)
      if (k + 1 == r.size() || r[k + 1] != r[k])
        points.push_back({r[k], static_cast<double>(k + 1) / static_cast<double>(profile.queries)});
    if (!points.empty() && points.front().x > 1) points.insert(points.begin(), {1, 0});
    profile.series.push_back(std::move(points));
  }
  return profile;
}

RuntimeScatter runtime_scatter(std::span<const QueryRun> a, std::span<const QueryRun> b) {
  if (a.size() != b.size())
    throw std::invalid_argument("runtime_scatter: " + std::to_string(a.size()) + " against " +
                                std::to_string(b.size()) + " queries");
  RuntimeScatter scatter;
  for (std::size_t q = 0; q < a.size(); ++q) {
    const bool a_done = is_completed(a[q].status), b_done = is_completed(b[q].status);
    if (!(a_done && a[q].runtime && b_done && b[q].runtime)) {
      scatter.one_only += a_done || b_done;
      continue;
    }
    if (*a[q].runtime <= 0 || *b[q].runtime <= 0) {
      ++scatter.zero;
      continue;
    }
    scatter.points.push_back({*a[q].runtime, *b[q].runtime});
    scatter.query.push_back(q);
  }
  return scatter;
}

}  // namespace mosb
