// The reverse CSR of §4 from the forward CSR: what the builder writes and what unpacking derives
// for encoding 4 (§6), one function for both.
#pragma once

#include <cstdint>
#include <span>

namespace mosb {

// The reverse CSR as the transpose of the forward CSR, each in-list in ascending arc id (§4), by
// one counting sort: in-degrees, their prefix sums, then every arc in id order put at its head's
// next free entry. `reverse_offsets` has n+1 entries, the other two m. Returns false, with the
// outputs undefined, when (offsets, targets) is not a CSR: offsets from 0 to m, never decreasing,
// every target below n, ids that fit u32.
bool derive_transpose(std::span<const std::uint64_t> offsets,
                      std::span<const std::uint32_t> targets, std::uint64_t* reverse_offsets,
                      std::uint32_t* reverse_sources, std::uint32_t* reverse_arcs);

}  // namespace mosb
