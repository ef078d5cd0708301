// The invalid packed golden files (spec/golden/1.1/packed/invalid and 1.2/packed/invalid): each
// is the valid grid.packed.mosb of its version with one fault a hostile or damaged download could
// carry, the table and header checksums resealed so that only decoding the sections can find it.
#pragma once

#include <string_view>

#include "file_patch.hpp"
#include "mosb/pack.hpp"

namespace mosb::testing {

struct PackedFault {
  const char* file;
  const char* expected;  // a fragment of the message mosb::load and mosb unpack give
  void (*apply)(Bytes&);
};

inline std::size_t encoded_section(const Bytes& b, format::Encoding encoding, std::size_t nth = 0) {
  for (std::size_t i = 0; i < header_of(b).section_count; ++i)
    if (entry_of(b, i).encoding == static_cast<std::uint8_t>(encoding) && nth-- == 0) return i;
  throw std::runtime_error("the packed golden file has no section in that encoding");
}

// Changes the table entry of the nth section in `encoding`, then reseals the header checksum.
template <class Change>
void patch_entry(Bytes& b, format::Encoding encoding, Change change, std::size_t nth = 0) {
  const auto i = encoded_section(b, encoding, nth);
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

// Faults of the transpose encoding (1.2), in the 1.2 grid.packed.mosb, whose three reverse CSR
// sections (offsets, sources, arcs, in table order) are derived.
inline const PackedFault kTransposeFaults[] = {
    {"transpose-not-reverse.mosb", "not part of the reverse CSR",
     [](Bytes& b) {
       patch_entry(b, Encoding::shuffle_zstd, [](SectionEntry& e) {
         e.encoding = static_cast<std::uint8_t>(Encoding::transpose);
         e.stored_length = 0;
       });
     }},
    {"transpose-stored.mosb", "transpose-encoded with stored length 64",
     [](Bytes& b) {
       patch_entry(b, Encoding::transpose, [](SectionEntry& e) { e.stored_length = 64; });
     }},
    {"transpose-missing-bit.mosb", "lacks the transpose-sections feature (bit 3)",
     [](Bytes& b) {
       auto h = header_of(b);
       h.required_features &= ~format::kFeatureTransposeSections;
       set_header(b, h);
       reseal_header(b);
     }},
    // reverse_arcs one entry longer than forward_targets: what it would allocate is not bounded.
    {"transpose-length.mosb", "section 'reverse_arcs' declares",
     [](Bytes& b) {
       patch_entry(
           b, Encoding::transpose, [](SectionEntry& e) { e.row_count += 1; }, 2);
     }},
    // The derived reverse_sources do not match the checksum the table holds.
    {"transpose-checksum.mosb", "checksum mismatch",
     [](Bytes& b) {
       patch_entry(
           b, Encoding::transpose, [](SectionEntry& e) { e.checksum ^= 1; }, 1);
     }},
    {"unknown-encoding.mosb", "unknown encoding 5",
     [](Bytes& b) {
       patch_entry(b, Encoding::delta_zstd, [](SectionEntry& e) { e.encoding = 5; });
     }},
};

// Faults of a packed solution file (1.6), in
// spec/golden/1.6/solutions/valid/fronts.packed.sol.mosb; the message fragment is the one
// SolutionReader::open and mosb unpack give.
inline std::size_t first_frame(const Bytes& b) {
  for (std::size_t i = 0; i < header_of(b).section_count; ++i)
    if (const auto encoding = entry_of(b, i).encoding; encoding >= 1 && encoding <= 3) return i;
  throw std::runtime_error("the packed golden solution file has no zstd frame");
}
template <class Change>
void patch_first_frame(Bytes& b, Change change) {
  auto e = entry_of(b, first_frame(b));
  change(e);
  set_entry(b, first_frame(b), e);
  reseal_header(b);
}

inline const PackedFault kPackedSolutionFaults[] = {
    // Packed, yet stating the minor of its layout: a 1.5 reader would not refuse it by version.
    {"packed-minor.sol.mosb", "a packed solution file states format 1.5, packed ones are 1.6",
     [](Bytes& b) {
       auto h = header_of(b);
       h.version_minor = 5;
       set_header(b, h);
       reseal_header(b);
     }},
    // The transpose encoding is an instance's reverse CSR's, even on a section of that kind.
    {"transpose.sol.mosb", "transpose encoding of a section that is not part of the reverse CSR",
     [](Bytes& b) {
       patch_first_frame(b, [](SectionEntry& e) {
         e.kind = static_cast<std::uint16_t>(format::SectionKind::reverse_offsets);
         e.encoding = static_cast<std::uint8_t>(Encoding::transpose);
         e.stored_length = 0;
       });
       auto h = header_of(b);
       h.required_features |= format::kFeatureTransposeSections;
       set_header(b, h);
       reseal_header(b);
     }},
    // A decoded length no frame of this size can produce (no header count bounds a front).
    {"bomb.sol.mosb", "zstd frame can hold",
     [](Bytes& b) { patch_first_frame(b, [](SectionEntry& e) { e.row_count = 1ULL << 40; }); }},
    {"declared-length.sol.mosb", "zstd frame declares",
     [](Bytes& b) { patch_first_frame(b, [](SectionEntry& e) { e.row_count += 1; }); }},
    {"truncated-frame.sol.mosb", "truncated or damaged",
     [](Bytes& b) { patch_first_frame(b, [](SectionEntry& e) { e.stored_length -= 5; }); }},
    {"section-checksum.sol.mosb", "mismatch",
     [](Bytes& b) { patch_first_frame(b, [](SectionEntry& e) { e.checksum ^= 1; }); }},
    // A non-zero byte in the gap after the first frame: decoding does not read it, the check
    // of the packed bytes' padding does.
    {"padding.sol.mosb", "[padding] byte",
     [](Bytes& b) {
       const auto e = entry_of(b, first_frame(b));
       if ((e.offset + e.stored_length) % format::kAlignment == 0)
         throw std::runtime_error("the first frame of the packed golden file leaves no gap");
       b[e.offset + e.stored_length] = std::byte{0x2A};
     }},
};

}  // namespace mosb::testing
