// The invalid packed golden files (spec/golden/1.1/packed/invalid): each is the valid
// grid.packed.mosb with one fault a hostile or damaged download could carry, the table and header
// checksums resealed so that only decoding the frames can find it.
#pragma once

#include <string_view>

#include "file_patch.hpp"

namespace mosb::testing {

struct PackedFault {
  const char* file;
  const char* expected;  // a fragment of the message GraphReader::load and mosb unpack give
  void (*apply)(Bytes&);
};

inline std::size_t encoded_section(const Bytes& b, format::Encoding encoding) {
  for (std::size_t i = 0; i < header_of(b).section_count; ++i)
    if (entry_of(b, i).encoding == static_cast<std::uint8_t>(encoding)) return i;
  throw std::runtime_error("the packed golden file has no section in that encoding");
}

// Changes the table entry of the first section in `encoding`, then reseals the header checksum.
template <class Change>
void patch_entry(Bytes& b, format::Encoding encoding, Change change) {
  const auto i = encoded_section(b, encoding);
  auto e = entry_of(b, i);
  change(e);
  set_entry(b, i, e);
  reseal_header(b);
}

using format::Encoding;
using format::SectionEntry;

inline const PackedFault kPackedFaults[] = {
    // The table declares one row more than the frame holds.
    {"declared-length.mosb", "zstd frame declares",
     [](Bytes& b) {
       patch_entry(b, Encoding::delta_zstd, [](SectionEntry& e) { e.row_count += 1; });
     }},
    // A decoded length no frame of this size can produce.
    {"bomb.mosb", "zstd frame can hold",
     [](Bytes& b) {
       patch_entry(b, Encoding::shuffle_zstd,
                   [](SectionEntry& e) { e.row_count = std::uint64_t{1} << 40; });
     }},
    {"truncated-frame.mosb", "truncated or damaged",
     [](Bytes& b) {
       patch_entry(b, Encoding::delta_zstd, [](SectionEntry& e) { e.stored_length -= 5; });
     }},
    // The frame decodes, but not to the elements the checksum covers.
    {"section-checksum.mosb", "mismatch",
     [](Bytes& b) {
       patch_entry(b, Encoding::shuffle_zstd, [](SectionEntry& e) { e.checksum ^= 1; });
     }},
    {"unknown-encoding.mosb", "encoding 4",
     [](Bytes& b) {
       patch_entry(b, Encoding::delta_zstd, [](SectionEntry& e) { e.encoding = 4; });
     }},
};

}  // namespace mosb::testing
