// libFuzzer target: arbitrary bytes through the solution-file reader: open (decoding a packed
// file, format 1.6), the payload checks, and, when they pass, every accessor a consumer such as
// `mosb eval` walks, then the checks against the instance (verify_solutions: path sums,
// disconnected claims, dominance) with the golden instance the golden solution files (the corpus)
// are bound to. Any outcome but a clean mosb::Error, a reported problem or success is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <vector>

#include "golden_input.hpp"
#include "header_checksum.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_verify.hpp"

namespace {

// spec/golden/1.0/valid/small.mosb, written once per process from the input behind it.
const mosb::GraphReader& golden_instance() {
  static const std::optional<mosb::GraphReader> instance = [] {
    const auto path = std::filesystem::temp_directory_path() /
                      ("mosb-fuzz-small-" + std::to_string(::getpid()) + ".mosb");
    mosb::write_graph(mosb::testing::golden_input(), path);
    auto reader = mosb::GraphReader::open(path, mosb::VerifyLevel::full);
    std::filesystem::remove(path);  // the mapping outlives the name
    return std::optional<mosb::GraphReader>(std::move(reader));
  }();
  return *instance;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& instance = golden_instance();
  // An 8-byte-aligned copy, as a memory mapping would be.
  std::vector<std::uint64_t> storage((size + 7) / 8);
  if (size > 0) std::memcpy(storage.data(), data, size);
  const auto bytes = std::as_writable_bytes(std::span(storage)).first(size);
  mosb_fuzz::repair_header_checksum(bytes);
  try {
    // A packed file is decoded as SolutionReader::open decodes it; the cap is well under
    // libFuzzer's -rss_limit_mb, so a bomb must be refused by it, not by the OOM.
    constexpr std::uint64_t kMaxMemory = std::uint64_t{256} << 20;
    const auto reader = mosb::SolutionReader::from_memory(bytes, "fuzz", kMaxMemory);
    (void)reader.digest();
    (void)reader.solver();
    (void)reader.stores_path_sums();
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
    (void)mosb::verify_solutions(reader, instance);
  } catch (const mosb::Error&) {
  }
  return 0;
}
