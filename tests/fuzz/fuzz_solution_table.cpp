// libFuzzer target: arbitrary bytes as a CSV/TSV solution table (parse_solution_table), columns by
// name and by position. Any outcome but a clean mosb::Error or in-range results is a bug.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/converters/solution_import.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.csv";
  static const std::string names[] = {"c1", "c2"};
  static const mosb::Query queries[] = {{0, 1}, {1, 0}, {1, 1}};
  for (bool pick : {false, true}) {
    for (unsigned id_base : {0u, 1u}) {
      mosb::converters::SolutionImportOptions options;
      options.objective_count = 2;
      options.vertex_count = 2;
      options.queries = queries;
      options.id_base = id_base;
      if (pick) options.columns = {1, 2};
      try {
        for (const auto& r : mosb::converters::parse_solution_table(text, name, names, options)) {
          if (r.query >= 3 || r.costs.size() % 2 != 0) __builtin_trap();
          for (double v : r.costs)
            if (!std::isfinite(v) || v < 0) __builtin_trap();
        }
      } catch (const mosb::Error&) {
      }
    }
  }
  return 0;
}
