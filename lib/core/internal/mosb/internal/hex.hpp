#pragma once

#include <cstdint>
#include <string>

namespace mosb {

// A checksum as text (spec/FORMAT.md §3): 16 lowercase hex digits, most significant first.
inline std::string hex64(std::uint64_t value) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4)
    out[static_cast<std::size_t>(i)] = kDigits[value & 0xF];
  return out;
}

}  // namespace mosb
