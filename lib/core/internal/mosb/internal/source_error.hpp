// The one shape of a refusal of a value in a text file mosb reads as configuration (a solver
// profile, an experiment file): "FILE:LINE:COLUMN: key 'KEY': problem".
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace mosb {

// The refusal as one line: LINE and COLUMN where known (> 0), the key part where KEY is not
// empty; a control character anywhere in it (a value quoted in the problem) as \xHH, so that a
// line break in the file cannot make two lines.
inline std::string source_error(std::string_view file, std::size_t line, std::size_t column,
                                std::string_view key, std::string_view problem) {
  std::string out(file);
  if (line > 0) out += ":" + std::to_string(line);
  if (line > 0 && column > 0) out += ":" + std::to_string(column);
  if (!key.empty()) out += ": key '" + std::string(key) + "'";
  out += ": ";
  out += problem;
  std::string shown;
  for (const char c : out) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x20 && byte != 0x7f) {
      shown += c;
      continue;
    }
    static constexpr char kDigits[] = "0123456789abcdef";
    shown += {'\\', 'x', kDigits[byte >> 4], kDigits[byte & 0xf]};
  }
  return shown;
}

}  // namespace mosb
