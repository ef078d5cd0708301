// libFuzzer target: arbitrary bytes as what a solver printed for `mosb run` (spec/RUN.md §3): as a
// front of 1, 2 or 3 objectives, each an integer or a float one (the objective count and the
// integer mask taken from the first byte), and as its standard error. The text is parsed whole and
// again fed in chunks split where the second byte says: both must give the same front (or the same
// refusal). Any outcome but a clean mosb::Error, a front of whole finite d-vectors (integers where
// the objective is one, at most 2^53), or statistics as documented is a bug.
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/solver_protocol.hpp"

namespace {

// The front of `text` fed `step` bytes at a time, or nullopt when it is refused.
std::optional<mosb::ProtocolFront> chunked(std::string_view text, std::size_t d,
                                           const std::vector<bool>& integer, std::size_t step) {
  try {
    mosb::ProtocolFrontParser parser(d, integer, "stdout");
    for (std::size_t at = 0; at < text.size(); at += step) parser.feed(text.substr(at, step));
    return parser.finish();
  } catch (const mosb::Error&) {
    return std::nullopt;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const std::size_t d = 1 + data[0] % 3;
  std::vector<bool> integer(d);
  for (std::size_t i = 0; i < d; ++i) integer[i] = (data[0] >> (2 + i)) & 1;
  const std::size_t step = 1 + data[1] % 17;
  const std::string_view text(reinterpret_cast<const char*>(data) + 2, size - 2);
  std::optional<mosb::ProtocolFront> whole;
  try {
    whole = mosb::parse_protocol_front(text, d, "stdout", integer);
    if (whole->costs.size() != whole->vectors * d) __builtin_trap();
    for (std::size_t k = 0; k < whole->costs.size(); ++k) {
      const double v = whole->costs[k];
      if (!std::isfinite(v)) __builtin_trap();
      if (integer[k % d] && (v < 0 || v != std::floor(v) || v > 9007199254740992.0))
        __builtin_trap();
    }
  } catch (const mosb::Error&) {
  }
  const auto pieces = chunked(text, d, integer, step);
  if (whole.has_value() != pieces.has_value()) __builtin_trap();
  if (whole && (whole->costs != pieces->costs || whole->vectors != pieces->vectors))
    __builtin_trap();
  try {
    const auto stats = mosb::parse_protocol_statistics(text, "stderr");
    if (stats.runtime_seconds &&
        (!std::isfinite(*stats.runtime_seconds) || *stats.runtime_seconds < 0))
      __builtin_trap();
    if (stats.expanded == UINT64_MAX || stats.generated == UINT64_MAX) __builtin_trap();
  } catch (const mosb::Error&) {
  }
  return 0;
}
