// libFuzzer target: arbitrary bytes as a PPA*/BOA*-style JSON log (parse_solver_json_log), records
// matched by position and by endpoints. Any outcome but a clean mosb::Error or in-range results is
// a bug.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/converters/solution_import.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.json";
  static const mosb::Query queries[] = {{0, 1}, {1, 0}, {0, 1}};
  for (auto match :
       {mosb::converters::RecordMatch::position, mosb::converters::RecordMatch::endpoints}) {
    mosb::converters::SolutionImportOptions options;
    options.objective_count = 2;
    options.vertex_count = 2;
    options.queries = queries;
    options.match = match;
    try {
      std::uint64_t previous = 0;
      bool first = true;
      for (const auto& r : mosb::converters::parse_solver_json_log(text, name, options)) {
        if (r.query >= 3 || r.costs.size() % 2 != 0 || (!first && r.query <= previous))
          __builtin_trap();
        for (double v : r.costs)
          if (!std::isfinite(v) || v < 0) __builtin_trap();
        previous = r.query;
        first = false;
      }
    } catch (const mosb::Error&) {
    }
  }
  return 0;
}
