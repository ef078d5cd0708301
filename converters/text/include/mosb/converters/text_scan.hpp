// Text primitives shared by the line-oriented parsers (DIMACS, FMI, Moving AI, GUARDS, roadmaps,
// query files): lines, blank-separated tokens with their columns, and the pieces of the one-line
// "FILE:LINE:COLUMN: message" errors.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/error.hpp"

namespace mosb::converters::text {

struct Token {
  std::string_view text;
  std::uint64_t column;  // 1-based
};

// What a line loses at its end; end-of-line columns (line.size() + 1) are counted after that.
enum class LineEnd {
  trim,  // a trailing run of '\r', blanks and tabs
  cr,    // one trailing '\r' only: trailing blanks are data (a Moving AI map row)
  keep,  // nothing (pair with Separators::blanks_and_cr so that a '\r' still ends a token)
};

// Text delivered in pieces (a file streamed through a bounded buffer). Every chunk but the last
// ends just after a '\n', so no line crosses two chunks.
class TextSource {
 public:
  virtual ~TextSource() = default;
  // The next chunk, valid until the following call; false at the end of the text.
  virtual bool next_chunk(std::string_view& chunk) = 0;
};

// Lines of a text buffer or of a TextSource, '\n' ending each; numbered from 1 across chunks. A
// line returned stays valid until the next call. Inline: it is on every parser's hot path.
class LineScanner {
 public:
  explicit LineScanner(std::string_view text, LineEnd end = LineEnd::trim)
      : text_(text), end_(end) {}
  explicit LineScanner(TextSource& source, LineEnd end = LineEnd::trim)
      : end_(end), source_(&source) {}

  bool next(std::string_view& line) {
    if (pos_ >= text_.size() && !refill()) return false;
    auto end = text_.find('\n', pos_);
    if (end == std::string_view::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    pos_ = end + 1;
    ++number_;
    if (end_ == LineEnd::trim) {
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t'))
        line.remove_suffix(1);
    } else if (end_ == LineEnd::cr) {
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    }
    return true;
  }

  // The number of the last line returned (0 before the first).
  std::uint64_t number() const { return number_; }

 private:
  // The source's next non-empty chunk; false at the end (or without a source).
  bool refill();

  std::string_view text_;
  LineEnd end_;
  TextSource* source_ = nullptr;
  std::size_t pos_ = 0;
  std::uint64_t number_ = 0;
};

enum class Separators { blanks, blanks_and_cr };  // blanks: ' ' and '\t'

// Splits a line into tokens, reusing `tokens` (cleared first) to spare an allocation per line.
void tokenize(std::string_view line, std::vector<Token>& tokens,
              Separators separators = Separators::blanks);

// A token quoted for a one-line message: control bytes and DEL shown as '?', long tokens cut
// after `limit` bytes with "...".
std::string quoted(std::string_view token, std::size_t limit = 40);
// For a std::string, an unqualified call would otherwise pick std::quoted (argument-dependent
// lookup).
inline std::string quoted(const std::string& token, std::size_t limit = 40) {
  return quoted(std::string_view(token), limit);
}

// Throws mosb::Error("FILE:LINE:COLUMN: message"); the second form's message names settings.
[[noreturn]] void fail(const std::string& file, std::uint64_t line, std::uint64_t column,
                       const std::string& message);
[[noreturn]] void fail(const std::string& file, std::uint64_t line, std::uint64_t column,
                       Message message);

// One or more decimal digits and nothing else.
bool is_digits(std::string_view s);

// Plain decimal digits (no sign, no blanks) whose value is at most `max`.
std::optional<std::uint64_t> to_u64(std::string_view s, std::uint64_t max = UINT64_MAX);

// An optional '-' then decimal digits, within the range of int64.
std::optional<std::int64_t> to_i64(std::string_view s);

// A finite real: digits, '.', an exponent, signs; no inf, nan or hex, no leading '+'.
std::optional<double> to_real(std::string_view s);

// "1 arc", "2 arcs"; "vertex" becomes "vertices".
std::string plural(std::uint64_t n, const char* word);

}  // namespace mosb::converters::text
