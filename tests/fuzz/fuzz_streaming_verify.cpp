// libFuzzer target, differential: arbitrary bytes (header checksum repaired) as a file, checked by
// verify_file at level full and by verify_file_streaming in its smallest budget (4 KiB: every large
// frame spilled, the transpose sorted in many buckets). Both must pass, with one digest, or both
// refuse; a crash, a sanitizer report or a hang is a bug too. Inputs whose decoding verify_file
// refuses for memory (past 64 MiB) are skipped: the streaming check would decode them in full.
// Seeds: the valid and invalid golden files, packed and not (tests/fuzz/run.sh).
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "header_checksum.hpp"
#include "mosb/error.hpp"
#include "mosb/pack.hpp"

namespace {

struct Outcome {
  bool ok = false;
  bool skip = false;
  std::string digest;
};

template <class Check>
Outcome outcome_of(Check check) {
  try {
    const auto found = check();
    return {!found.problem.has_value(), false, found.digest};
  } catch (const mosb::Error& error) {
    return {false, error.code() == mosb::ErrorCode::no_memory, ""};
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::byte> bytes(size);
  if (size > 0) std::memcpy(bytes.data(), data, size);
  mosb_fuzz::repair_header_checksum(bytes);
  const int fd = ::memfd_create("mosb-fuzz", MFD_CLOEXEC);
  if (fd < 0) return 0;
  if (::write(fd, bytes.data(), bytes.size()) != static_cast<ssize_t>(bytes.size())) {
    ::close(fd);
    return 0;
  }
  const std::filesystem::path path = "/proc/self/fd/" + std::to_string(fd);
  const auto expected = outcome_of(
      [&] { return mosb::verify_file(path, mosb::VerifyLevel::full, std::uint64_t{64} << 20); });
  if (!expected.skip) {
    const auto streamed = outcome_of([&] {
      return mosb::verify_file_streaming(path, {4096, std::filesystem::temp_directory_path()});
    });
    if (streamed.ok != expected.ok || (expected.ok && streamed.digest != expected.digest))
      __builtin_trap();
  }
  ::close(fd);
  return 0;
}
