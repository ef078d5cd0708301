// libFuzzer target: arbitrary bytes through unpack_bytes (the decoder of packed files: frame
// content sizes, the decoded-length bound, the row counts the header gives, the memory cap,
// un-shuffling and running sums, checksums), then the decoded image through the reader and verify,
// and the packed bytes' own padding check. Any outcome but a clean mosb::Error or success (a crash,
// a sanitizer report, a hang, an allocation beyond the cap) is a bug. Seeds: the valid and invalid
// packed golden files (tests/fuzz/run.sh).
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
    // A cap well under libFuzzer's -rss_limit_mb: a bomb must be refused by it, not by the OOM.
    constexpr std::uint64_t kMaxMemory = std::uint64_t{256} << 20;
    const auto image = mosb::unpack_bytes(bytes, "fuzz", kMaxMemory);
    const auto reader = mosb::GraphReader::from_memory(image.bytes, "fuzz");
    (void)mosb::verify(reader, mosb::VerifyLevel::full);
    (void)mosb::find_padding_problem(mosb::GraphReader::from_memory(bytes, "fuzz"));
  } catch (const mosb::Error&) {
  }
  return 0;
}
