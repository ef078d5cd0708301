// libFuzzer target: arbitrary bytes as one per-query front file (parse_front_text), with and
// without --columns, and as an example solver's run log (apply_example_run_log) over fronts for
// both queries. Any outcome but a clean mosb::Error, a front of whole, finite, non-negative
// d-vectors, or statistics that are finite and non-negative is a bug.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/converters/solution_import.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.front";
  static const mosb::Query queries[] = {{0, 1}, {1, 0}};
  for (bool pick : {false, true}) {
    mosb::converters::SolutionImportOptions options;
    options.objective_count = 2;
    options.vertex_count = 2;
    options.queries = queries;
    if (pick) options.columns = {2, 0};
    try {
      const auto result = mosb::converters::parse_front_text(text, name, 1, options);
      if (result.query != 1 || result.costs.size() % 2 != 0) __builtin_trap();
      for (double v : result.costs)
        if (!std::isfinite(v) || v < 0) __builtin_trap();
      // A stated status other than solved has no front; an exit status only on failed.
      if (result.status != mosb::QueryStatus::solved && !result.costs.empty()) __builtin_trap();
      if (result.statistics.exit_status && result.status != mosb::QueryStatus::failed)
        __builtin_trap();
      if (result.vector_sources.size() * 2 != result.costs.size()) __builtin_trap();
    } catch (const mosb::Error&) {
    }
  }
  mosb::converters::SolutionImportOptions options;
  options.objective_count = 2;
  options.vertex_count = 2;
  options.queries = queries;
  std::vector<mosb::converters::ImportedResult> results(2);
  results[0] = {0, mosb::QueryStatus::solved, {1, 2}, {}};
  results[1] = {1, mosb::QueryStatus::disconnected, {}, {}};
  try {
    mosb::converters::apply_example_run_log(text, "fuzz.log", options, results);
    for (const auto& r : results)
      if (!r.statistics.runtime_seconds || !std::isfinite(*r.statistics.runtime_seconds) ||
          *r.statistics.runtime_seconds < 0 || !r.statistics.expanded)
        __builtin_trap();
  } catch (const mosb::Error&) {
  }
  return 0;
}
