// libFuzzer target: arbitrary bytes as a MANIFEST (a download, so untrusted): parse_manifest, and
// serialize_manifest of what it accepts, which must parse back to the same solution entries. Any
// outcome but success or a clean mosb::Error is a bug, and so is an accepted file name that a
// terminal would not show as itself (the name rule, spec/MANIFEST.md: escape_for_terminal may only
// double its backslashes).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/error.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/manifest.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const auto manifest = mosb::parse_manifest(text, "MANIFEST");
    for (const auto& e : manifest.entries) {
      std::string shown;
      for (const char c : e.file) shown += c == '\\' ? std::string("\\\\") : std::string(1, c);
      if (mosb::escape_for_terminal(e.file) != shown) __builtin_trap();
    }
    // A solution file's entry (version 2) reads back as it was written.
    const auto again = mosb::parse_manifest(mosb::serialize_manifest(manifest), "again");
    if (again.entries.size() != manifest.entries.size()) __builtin_trap();
    for (std::size_t i = 0; i < again.entries.size(); ++i)
      if (again.entries[i].solutions != manifest.entries[i].solutions) __builtin_trap();
  } catch (const mosb::Error&) {
  }
  return 0;
}
