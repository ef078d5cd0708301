// libFuzzer target: arbitrary bytes through the DIMACS-Extended elevation parser (both id bases,
// several vertex counts) and the --view parser. Any outcome but a clean mosb::Error or success is a
// bug.
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/converters/dimacs_extended.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.elev";
  for (unsigned id_base : {0u, 1u})
    for (std::uint64_t n : {0u, 1u, 3u}) {
      try {
        const auto elevation = mosb::converters::parse_dimacs_elevation(text, name, id_base, n);
        if (elevation.size() != n) __builtin_trap();
      } catch (const mosb::Error&) {
      }
    }
  try {
    const auto view = mosb::parse_view_spec(text);
    if (view.name.empty() || view.objectives.empty() || view.queries.empty()) __builtin_trap();
  } catch (const mosb::Error&) {
  }
  return 0;
}
