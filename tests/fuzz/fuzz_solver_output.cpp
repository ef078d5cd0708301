// libFuzzer target: arbitrary bytes as what a solver printed for `mosb run` (spec/RUN.md §3): as a
// front of 1, 2 or 3 objectives (parse_protocol_front, the objective count taken from the first
// byte) and as its standard error (parse_protocol_statistics). Any outcome but a clean mosb::Error,
// a front of whole finite d-vectors, or statistics as documented is a bug.
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/error.hpp"
#include "mosb/solver_protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::size_t d = 1 + data[0] % 3;
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  try {
    const auto front = mosb::parse_protocol_front(text, d, "stdout");
    if (front.costs.size() != front.vectors * d) __builtin_trap();
    for (double v : front.costs)
      if (!std::isfinite(v)) __builtin_trap();
  } catch (const mosb::Error&) {
  }
  try {
    const auto stats = mosb::parse_protocol_statistics(text, "stderr");
    if (stats.runtime_seconds &&
        (!std::isfinite(*stats.runtime_seconds) || *stats.runtime_seconds < 0))
      __builtin_trap();
    for (const auto& [key, value] : stats.other)
      if (key.empty() || key == "expanded" || key == "generated" || key == "runtime_seconds")
        __builtin_trap();
  } catch (const mosb::Error&) {
  }
  return 0;
}
