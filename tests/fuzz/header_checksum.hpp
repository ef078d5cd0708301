// The fuzz targets' mosb inputs get a correct header checksum before the library sees them, so a
// mutation reaches the checks behind it (feature bits, section entries, the payload) instead of
// stopping at "header checksum mismatch". The library itself keeps that check in every build, so
// the fuzz targets and the sanitized tests share one build (the `sanitize` preset).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include "mosb/checksum.hpp"
#include "mosb/format.hpp"

namespace mosb_fuzz {

// When the bytes hold a 128-byte header whose section table ends at the end of the file (the
// reader's rule before it checks the checksum), writes XXH3-64 of header bytes [0, 120) followed by
// the table into the header's checksum field; otherwise leaves the bytes as they are.
inline void repair_header_checksum(std::span<std::byte> bytes) {
  namespace format = mosb::format;
  if (bytes.size() < format::kHeaderSize) return;
  format::FileHeader header;
  std::memcpy(&header, bytes.data(), sizeof header);
  // A u32 count of 64-byte entries cannot overflow 64 bits.
  const std::uint64_t table_bytes =
      std::uint64_t{header.section_count} * sizeof(format::SectionEntry);
  if (header.table_offset < format::kHeaderSize || header.table_offset > bytes.size() ||
      table_bytes != bytes.size() - header.table_offset)
    return;
  std::vector<std::byte> covered(bytes.begin(), bytes.begin() + format::kHeaderChecksumOffset);
  covered.insert(covered.end(), bytes.begin() + static_cast<std::ptrdiff_t>(header.table_offset),
                 bytes.end());
  const std::uint64_t checksum = mosb::xxh3_64(covered.data(), covered.size());
  std::memcpy(bytes.data() + format::kHeaderChecksumOffset, &checksum, sizeof checksum);
}

}  // namespace mosb_fuzz
