// The rules of verification (spec/FORMAT.md §9) over spans of elements, shared by verify() on a
// mapped file and the streaming check of pack (verify_file_streaming), which sees a section one
// chunk at a time: one wording of every message, one scan of every rule.
#pragma once

#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "mosb/container.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/metadata.hpp"

namespace mosb::rules {

using Problem = std::optional<std::string>;

// The sequential scans below vectorize; on x86-64 each is also built for AVX2 and picked at run
// time (twice the width of the baseline's SSE2: the FLA-size file's structure pass, 2.0 -> 1.4 ms
// before the transpose).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define MOSB_SCAN_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MOSB_SCAN_CLONES
#endif

inline std::string in_section(const Section& s, std::string_view rule, const std::string& detail) {
  return "section '" + s.name + "': [" + std::string(rule) + "] " + detail;
}

inline Problem checksum_problem(const Section& s, std::uint64_t computed) {
  if (computed != s.entry.checksum)
    return in_section(
        s, "checksum",
        "mismatch (stored " + hex64(s.entry.checksum) + ", computed " + hex64(computed) + ")");
  return std::nullopt;
}

// Branch-free scans, without a message: they vectorize.
bool offsets_ascend(std::span<const std::uint64_t> offsets);
// An OR of comparisons, not an unsigned maximum, which plain x86-64 cannot vectorize.
bool ids_below(std::span<const std::uint32_t> ids, std::uint64_t n);

// Offsets never decrease; `first` is the index of offsets[0] within the section.
Problem check_offsets(const Section& s, std::span<const std::uint64_t> offsets,
                      std::uint64_t first = 0);
// Every id below n (rule `rule`, "WHAT i is vertex ..."); `first` as above.
Problem check_ids(const Section& s, std::span<const std::uint32_t> ids, std::uint64_t n,
                  std::string_view rule, std::string_view what, std::uint64_t first = 0);

// Float costs (rules cost-*, "arc 3 costs ...") and query references (reference-*, "query 3 has
// ...") are finite and >= 0; `first` as above.
template <class T>
Problem check_float_values(const Section& s, std::span<const T> values, std::string_view rule,
                           std::string_view row, std::string_view verb, std::uint64_t first = 0) {
  bool all_good = true;
  for (const T value : values) all_good &= std::isfinite(value) & (value >= 0);
  if (all_good) return std::nullopt;
  for (std::size_t a = 0; a < values.size(); ++a) {
    const bool finite = std::isfinite(values[a]);
    if (!finite || values[a] < 0)
      return in_section(s, std::string(rule) + (finite ? "-nonnegative" : "-finite"),
                        std::string(row) + " " + std::to_string(first + a) + " " +
                            std::string(verb) + " " + std::to_string(values[a]));
  }
  return std::nullopt;
}

// The metadata rules of §7 and §9 (views, value sets, query references) on the parsed metadata
// of `reader`'s file.
Problem metadata_problem(const GraphReader& reader, const Metadata& metadata);

}  // namespace mosb::rules
