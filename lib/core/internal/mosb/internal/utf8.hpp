#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace mosb {

// Length of the well-formed UTF-8 sequence starting at s[i] (RFC 3629: no overlongs, no
// surrogates, at most U+10FFFF), or 0 when the bytes there are not one.
inline std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t length;
  unsigned char low = 0x80, high = 0xBF;  // allowed range of the second byte
  if (b0 >= 0xC2 && b0 <= 0xDF)
    length = 2;
  else if (b0 >= 0xE0 && b0 <= 0xEF) {
    length = 3;
    if (b0 == 0xE0) low = 0xA0;
    if (b0 == 0xED) high = 0x9F;
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    length = 4;
    if (b0 == 0xF0) low = 0x90;
    if (b0 == 0xF4) high = 0x8F;
  } else {
    return 0;
  }
  if (i + length > s.size()) return 0;
  if (byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k)
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  return length;
}

inline bool is_valid_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto length = utf8_sequence_length(s, i);
    if (length == 0) return false;
    i += length;
  }
  return true;
}

// The code point of the well-formed sequence of `length` bytes at s[i] (utf8_sequence_length).
inline std::uint32_t utf8_code_point(std::string_view s, std::size_t i, std::size_t length) {
  const auto lead = static_cast<unsigned char>(s[i]);
  if (length == 1) return lead;
  std::uint32_t code = lead & (0xFF >> (length + 1));
  for (std::size_t k = 1; k < length; ++k)
    code = (code << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
  return code;
}

// True for the code points above ASCII that a terminal does not show as themselves: C1 controls
// (U+0080-U+009F, e.g. the 8-bit CSI), line and paragraph separators, and the bidirectional
// overrides, isolates and marks, which reorder what follows. escape_for_terminal writes them as
// `\u{XXXX}`; a MANIFEST file name may hold none of them (is_valid_manifest_file_name).
inline bool is_hidden_code_point(std::uint32_t code) {
  return (code >= 0x80 && code <= 0x9F) || code == 0x2028 || code == 0x2029 ||
         (code >= 0x202A && code <= 0x202E) || (code >= 0x2066 && code <= 0x2069) ||
         code == 0x200E || code == 0x200F || code == 0x061C ||
         // Invisible format characters (Unicode Cf): zero-width space, joiners, word joiner and
         // invisible operators, the byte order mark, the soft hyphen and the Mongolian vowel
         // separator. A name holding one prints like another name.
         (code >= 0x200B && code <= 0x200D) || (code >= 0x2060 && code <= 0x2064) ||
         (code >= 0x206A && code <= 0x206F) || code == 0xFEFF || code == 0x00AD || code == 0x180E ||
         (code >= 0xFFF9 && code <= 0xFFFB);
}

// Text from a file, made safe to print on a terminal as one line: `\` becomes `\\`, LF `\n`, CR
// `\r`, tab `\t`, other C0 controls and DEL `\xHH`; C1 controls (U+0080-U+009F, e.g. the 8-bit
// CSI), line/paragraph separators and bidirectional overrides `\u{XXXX}`; bytes that are not UTF-8
// `\xHH`. So a value can neither move the cursor, recolour, reorder nor fake a line.
inline std::string escape_for_terminal(std::string_view s) {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(s.size());
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    const auto length = utf8_sequence_length(s, i);
    if (length == 1 && c >= 0x20 && c != 0x7F && c != '\\') {
      out += static_cast<char>(c);
    } else if (length == 1) {
      if (c == '\\')
        out += "\\\\";
      else if (c == '\n')
        out += "\\n";
      else if (c == '\r')
        out += "\\r";
      else if (c == '\t')
        out += "\\t";
      else
        out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
    } else if (length == 0) {
      out += std::string("\\x") + kHex[c >> 4] + kHex[c & 15];
      i += 1;
      continue;
    } else {
      const std::uint32_t code = utf8_code_point(s, i, length);
      if (is_hidden_code_point(code)) {
        out += "\\u{";
        for (int shift = 12; shift >= 0; shift -= 4) out += kHex[(code >> shift) & 15];
        out += '}';
      } else {
        out.append(s.substr(i, length));
      }
    }
    i += length;
  }
  return out;
}

}  // namespace mosb
