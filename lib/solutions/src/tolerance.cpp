#include "tolerance.hpp"

#include <algorithm>
#include <string>

#include "mosb/error.hpp"
#include "mosb/internal/number_text.hpp"

namespace mosb::solutions_internal {

std::vector<bool> float_objectives(const SolutionReader& a, const SolutionReader& b) {
  std::vector<bool> result;
  for (std::size_t i = 0; i < a.objective_count(); ++i)
    result.push_back(format::is_float(a.objective_type(i)) ||
                     format::is_float(b.objective_type(i)));
  return result;
}

void check_tolerance(double tolerance) {
  if (tolerance >= 0 && tolerance < 1) return;
  throw Error(ErrorCode::invalid_argument, "tolerance " + shortest_text(tolerance) +
                                               " is not a relative tolerance in [0, 1) "
                                               "(0: exact comparison)");
}

void snap_within_tolerance(std::span<double> a, std::span<double> b, std::size_t d,
                           const std::vector<bool>& snap, double tolerance) {
  check_tolerance(tolerance);
  if (tolerance == 0 || d == 0) return;
  std::vector<double> values, first;
  for (std::size_t i = 0; i < d && i < snap.size(); ++i) {
    if (!snap[i]) continue;
    values.clear();
    for (const auto front : {a, b})
      for (std::size_t k = i; k < front.size(); k += d) values.push_back(front[k]);
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    first.resize(values.size());
    for (std::size_t k = 0; k < values.size(); ++k) {
      const bool same = k > 0 && values[k] <= first[k - 1] + first[k - 1] * tolerance;
      first[k] = same ? first[k - 1] : values[k];
    }
    for (const auto front : {a, b})
      for (std::size_t k = i; k < front.size(); k += d) {
        const auto at = std::lower_bound(values.begin(), values.end(), front[k]) - values.begin();
        front[k] = first[static_cast<std::size_t>(at)];
      }
  }
}

}  // namespace mosb::solutions_internal
