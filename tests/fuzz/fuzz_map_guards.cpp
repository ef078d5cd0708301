// libFuzzer target: arbitrary bytes as the metadata value map.guards of an instance (a download,
// so untrusted), parsed for a 1000 x 700 map. Any outcome but guards on the map or a clean
// mosb::Error is a bug.
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "mosb/error.hpp"
#include "mosb/report/figures.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    for (const auto& g : mosb::plots::parse_guard_cells(text, 1000, 700, "fuzz"))
      if (!(g.x >= 0 && g.x < 1000 && g.y >= 0 && g.y < 700)) std::abort();
  } catch (const mosb::Error&) {
  }
  return 0;
}
