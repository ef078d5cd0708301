// libFuzzer target: arbitrary bytes as a MANIFEST (a download, so untrusted): parse_manifest, and
// serialize_manifest of what it accepts. Any outcome but success or a clean mosb::Error is a bug.
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/error.hpp"
#include "mosb/manifest.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto manifest = mosb::parse_manifest(text, "MANIFEST");
    (void)mosb::serialize_manifest(manifest);
  } catch (const mosb::Error&) {
  }
  return 0;
}
