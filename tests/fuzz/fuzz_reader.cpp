// libFuzzer target: arbitrary bytes through open, every verify level and every accessor. Any
// outcome but a clean mosb::Error or success (a crash, a sanitizer report, a hang) is a bug.
#include <cstdint>
#include <cstring>
#include <vector>

#include "header_checksum.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/verify.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // An 8-byte-aligned copy, as a memory mapping would be.
  std::vector<std::uint64_t> storage((size + 7) / 8);
  if (size > 0) std::memcpy(storage.data(), data, size);
  const auto bytes = std::as_writable_bytes(std::span(storage)).first(size);
  mosb_fuzz::repair_header_checksum(bytes);
  try {
    auto reader = mosb::GraphReader::from_memory(bytes, "fuzz");
    (void)reader.digest();
    for (auto level : {mosb::VerifyLevel::checksums, mosb::VerifyLevel::structure}) {
      try {
        (void)mosb::verify(reader, level);
      } catch (const mosb::Error&) {
      }
    }
    (void)reader.metadata().entries().size();
    std::vector<double> costs(reader.arc_count());
    for (std::size_t i = 0; i < reader.objective_count(); ++i) reader.read_cost_as(i, costs);
    for (const auto* s : reader.all(mosb::format::SectionKind::queries))
      (void)reader.queries(s->name);
  } catch (const mosb::Error&) {
  }
  return 0;
}
