#include "mosb/version.hpp"

namespace mosb {
const char* version() noexcept {
  return MOSB_VERSION_STRING;
}
}  // namespace mosb
