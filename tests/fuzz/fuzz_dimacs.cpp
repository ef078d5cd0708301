// libFuzzer target: arbitrary bytes through the DIMACS .gr and .co text parsers, with both id bases
// and against a reference graph. Any outcome but a clean mosb::Error or success is a bug.
#include <cstdint>
#include <string>
#include <string_view>

#include "mosb/converters/dimacs_converter.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  static const std::string name = "fuzz.gr";
  static const std::string reference_name = "reference.gr";
  static const auto reference =
      mosb::converters::parse_dimacs_gr("p sp 3 2\na 1 2 1\na 2 3 1\n", reference_name, 1);
  for (unsigned id_base : {0u, 1u}) {
    try {
      const auto g = mosb::converters::parse_dimacs_gr(text, name, id_base);
      for (std::size_t k = 0; k < g.tails.size(); ++k)
        if (g.tails[k] >= g.vertex_count || g.heads[k] >= g.vertex_count) __builtin_trap();
    } catch (const mosb::Error&) {
    }
    try {
      const mosb::converters::DimacsReference ref{&reference_name, &reference};
      (void)mosb::converters::parse_dimacs_gr(text, name, id_base, &ref);
    } catch (const mosb::Error&) {
    }
    try {
      (void)mosb::converters::parse_dimacs_co(text, name, id_base, 3);
    } catch (const mosb::Error&) {
    }
  }
  return 0;
}
