// XXH3-64, the hash of every section checksum and of `source.input.<i>.xxh3` (spec/FORMAT.md §3),
// on the widest vector unit the CPU has (libxxhash's run-time dispatch on x86-64).
#pragma once

#include <cstddef>
#include <cstdint>

namespace mosb {

std::uint64_t xxh3_64(const void* data, std::size_t size);

}  // namespace mosb
