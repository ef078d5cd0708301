// libFuzzer target: arbitrary bytes through the query-file parser, with both id bases, with and
// without --match. Any outcome but a clean mosb::Error or in-range pairs is a bug.
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/converters/query_import.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.queries";
  for (unsigned id_base : {0u, 1u}) {
    for (const char* match : {static_cast<const char*>(nullptr), "g"}) {
      mosb::converters::QueryFileOptions options;
      options.id_base = id_base;
      options.vertex_count = 100;
      if (match) options.match = match;
      try {
        for (const auto& q : mosb::converters::parse_query_file(text, name, options))
          if (q.start >= options.vertex_count || q.goal >= options.vertex_count) __builtin_trap();
      } catch (const mosb::Error&) {
      }
    }
  }
  return 0;
}
