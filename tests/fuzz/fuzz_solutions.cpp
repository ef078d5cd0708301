// libFuzzer target: arbitrary bytes through the solution-file reader: open, the payload checks,
// and, when they pass, every accessor a consumer such as `mosb eval` walks. Any outcome but a clean
// mosb::Error or success is a bug.
#include <cstdint>
#include <cstring>
#include <vector>

#include "header_checksum.hpp"
#include "mosb/solution_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // An 8-byte-aligned copy, as a memory mapping would be.
  std::vector<std::uint64_t> storage((size + 7) / 8);
  if (size > 0) std::memcpy(storage.data(), data, size);
  const auto bytes = std::as_writable_bytes(std::span(storage)).first(size);
  mosb_fuzz::repair_header_checksum(bytes);
  try {
    const auto reader = mosb::SolutionReader::from_memory(bytes, "fuzz");
    (void)reader.digest();
    (void)reader.solver();
    if (reader.verify_payload()) return 0;  // consumers stop at a reported problem
    for (std::uint64_t q = 0; q < reader.query_count(); ++q) {
      (void)reader.status(q);
      (void)reader.statistics(q);
      const auto first = reader.front_begin(q);
      for (std::uint64_t row = first; row < first + reader.front_size(q); ++row) {
        for (std::size_t i = 0; i < reader.objective_count(); ++i)
          (void)reader.value_as_double(i, row);
        (void)reader.path(row);
      }
    }
  } catch (const mosb::Error&) {
  }
  return 0;
}
