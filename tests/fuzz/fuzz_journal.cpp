// libFuzzer target: arbitrary bytes as a `mosb run` journal that --resume reads (spec/RUN.md §6),
// a file a user may have edited by hand. Read whole (the checksums, the binding, every record)
// and, since random bytes seldom pass a checksum, also as one record's JSON (record_from_json). Any
// outcome but a clean mosb::Error or records as documented is a bug.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "journal.hpp"
#include "mosb/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  char path[] = "/tmp/mosb-fuzz-journal-XXXXXX";
  const int fd = ::mkstemp(path);
  if (fd < 0) return 0;
  const bool written = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  ::close(fd);
  if (written) {
    try {
      // The journal's own binding when its first line has one, so mutated records get past the
      // binding check; a fixed one otherwise.
      mosb::run_internal::JournalBinding binding{
          {{"instance_digest", "0123456789abcdef0123456789abcdef"}, {"queries", 4}},
          std::string(64, 'a'),
          (size & 1) != 0};
      try {
        const auto header = nlohmann::json::parse(text.substr(0, text.find('\n')));
        binding.settings = header.at("binding");
        binding.executable_sha256 = header.at("executable_sha256").get<std::string>();
      } catch (const nlohmann::json::exception&) {
      }
      mosb::run_internal::Journal journal(
          path, binding, true, [](const mosb::QueryRecord& r) -> std::optional<std::string> {
            if (r.query >= 4) return "out of range";
            return std::nullopt;
          });
      for (const auto& [q, record] : journal.records())
        if (q != record.query || q >= 4 || record.status == mosb::QueryStatus::not_run)
          __builtin_trap();
    } catch (const mosb::Error&) {
    }
  }
  ::unlink(path);
  try {
    const auto j = nlohmann::json::parse(text);
    const auto record = mosb::run_internal::record_from_json(j);
    if (record.status == mosb::QueryStatus::not_run) __builtin_trap();
  } catch (const nlohmann::json::exception&) {
  } catch (const mosb::Error&) {
  }
  return 0;
}
