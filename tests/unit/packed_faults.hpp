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

inline const PackedFault kPackedFaults[] = {
    {"declared-length.mosb", "zstd frame declares",
     [](Bytes& b) {  // the table declares one row more than the frame holds
       const auto i = encoded_section(b, format::Encoding::delta_zstd);
       auto e = entry_of(b, i);
       e.row_count += 1;
       set_entry(b, i, e);
       reseal_header(b);
     }},
    {"bomb.mosb", "zstd frame can hold",
     [](Bytes& b) {  // a decoded length no frame of this size can produce
       const auto i = encoded_section(b, format::Encoding::shuffle_zstd);
       auto e = entry_of(b, i);
       e.row_count = std::uint64_t{1} << 40;
       set_entry(b, i, e);
       reseal_header(b);
     }},
    {"truncated-frame.mosb", "truncated or damaged",
     [](Bytes& b) {
       const auto i = encoded_section(b, format::Encoding::delta_zstd);
       auto e = entry_of(b, i);
       e.stored_length -= 5;
       set_entry(b, i, e);
       reseal_header(b);
     }},
    {"section-checksum.mosb", "mismatch",
     [](Bytes& b) {  // the frame decodes, but not to the elements the checksum covers
       const auto i = encoded_section(b, format::Encoding::shuffle_zstd);
       auto e = entry_of(b, i);
       e.checksum ^= 1;
       set_entry(b, i, e);
       reseal_header(b);
     }},
    {"unknown-encoding.mosb", "encoding 4",
     [](Bytes& b) {
       const auto i = encoded_section(b, format::Encoding::delta_zstd);
       auto e = entry_of(b, i);
       e.encoding = 4;
       set_entry(b, i, e);
       reseal_header(b);
     }},
};

}  // namespace mosb::testing
