// The one text of a double that mosb writes where it must read back exactly (limits, metadata,
// messages): the shortest that does.
#pragma once

#include <charconv>
#include <string>

namespace mosb {

// std::to_chars' shortest round-trip form ("0.1", "1e+300"; "inf", "-inf", "nan" as it writes
// them). No precondition: every double has one, of at most 24 characters.
inline std::string shortest_text(double value) {
  char text[32];
  return {text, std::to_chars(text, text + sizeof text, value).ptr};
}

}  // namespace mosb
