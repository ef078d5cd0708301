#include "mosb/checksum.hpp"

#include "mosb/internal/xxh3.hpp"

namespace mosb {

std::uint64_t xxh3_64(const void* data, std::size_t size) {
  return XXH3_64bits(data, size);
}

}  // namespace mosb
