#include "mosb/solution_summary.hpp"

#include <algorithm>

namespace mosb {

namespace {

StatisticSummary summarize(const SolutionReader& r, Statistic statistic) {
  StatisticSummary summary{statistic};
  for (std::uint64_t q = 0; q < r.query_count(); ++q) {
    std::optional<double> value;
    if (statistic == Statistic::runtime_seconds) {
      value = r.runtime_seconds(q);
    } else if (const auto count = r.count_statistic(statistic, q)) {
      value = static_cast<double>(*count);
    }
    if (!value) continue;
    ++summary.queries;
    summary.total += *value;
    summary.max = std::max(summary.max, *value);
  }
  return summary;
}

}  // namespace

SolutionSummary summarize(const SolutionReader& r) {
  SolutionSummary summary;
  std::vector<std::uint64_t> sizes;
  for (std::uint64_t q = 0; q < r.query_count(); ++q) {
    const auto status = r.status(q);
    ++summary.status_counts[static_cast<std::size_t>(status)];
    if (status == QueryStatus::solved) sizes.push_back(r.front_size(q));
  }
  std::sort(sizes.begin(), sizes.end());
  if (!sizes.empty())
    summary.front_sizes = FrontSizes{sizes.front(), sizes[(sizes.size() - 1) / 2], sizes.back()};
  for (const auto statistic : kStatistics)
    if (r.has_statistic(statistic)) summary.statistics.push_back(summarize(r, statistic));
  return summary;
}

}  // namespace mosb
