#pragma once

namespace mosb {
// The release of the mosb library and tool (not the file format version, which is in format.hpp).
inline constexpr const char* kVersion = "0.1.0";
}  // namespace mosb
