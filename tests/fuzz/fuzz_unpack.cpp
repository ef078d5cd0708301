// libFuzzer target: arbitrary bytes through unpack_bytes (the decoder of packed files: frame
// content sizes, the decoded-length bound, un-shuffling and running sums, checksums), then the
// decoded image through the reader and verify. Any outcome but a clean mosb::Error or success (a
// crash, a sanitizer report, a hang, an allocation beyond the bound) is a bug.
#include <cstdint>
#include <cstring>
#include <vector>

#include "header_checksum.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/pack.hpp"
#include "mosb/verify.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint64_t> storage((size + 7) / 8);
  if (size > 0) std::memcpy(storage.data(), data, size);
  const auto bytes = std::as_writable_bytes(std::span(storage)).first(size);
  mosb_fuzz::repair_header_checksum(bytes);
  try {
    const auto image = mosb::unpack_bytes(bytes, "fuzz");
    const auto reader = mosb::GraphReader::from_memory(image.bytes, "fuzz");
    (void)mosb::verify(reader, mosb::VerifyLevel::full);
  } catch (const mosb::Error&) {
  }
  return 0;
}
