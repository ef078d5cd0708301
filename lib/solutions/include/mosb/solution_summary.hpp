// What `mosb solutions inspect` reports of a solution file (the paper's Table 1 columns): queries
// per status, front sizes over the solved queries, and each statistic's count, total and maximum.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "mosb/solution_file.hpp"

namespace mosb {

struct FrontSizes {
  std::uint64_t min = 0, median = 0, max = 0;
};

struct StatisticSummary {
  Statistic statistic;
  std::uint64_t queries = 0;  // that carry a value
  double total = 0, max = 0;
};

struct SolutionSummary {
  std::array<std::uint64_t, kLastQueryStatus + 1> status_counts{};  // indexed by QueryStatus
  // Over the solved queries; the median of an even count is the lower middle one (a front
  // cardinality, never a fraction). nullopt when no query is solved.
  std::optional<FrontSizes> front_sizes;
  std::vector<StatisticSummary> statistics;  // the statistics the file has, in kStatistics order
};

// O(Q log Q) over the statuses and front offsets; `solutions` must be verified (open_verified).
SolutionSummary summarize(const SolutionReader& solutions);

}  // namespace mosb
