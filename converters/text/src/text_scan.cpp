#include "mosb/converters/text_scan.hpp"

#include <charconv>
#include <cmath>

#include "mosb/error.hpp"

namespace mosb::converters::text {

namespace {

template <class IsSeparator>
void split(std::string_view line, std::vector<Token>& tokens, IsSeparator is_separator) {
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_separator(line[i])) ++i;
    if (i >= line.size()) break;
    const std::size_t start = i;
    while (i < line.size() && !is_separator(line[i])) ++i;
    tokens.push_back({line.substr(start, i - start), start + 1});
  }
}

}  // namespace

bool LineScanner::refill() {
  if (source_ == nullptr) return false;
  std::string_view chunk;
  while (source_->next_chunk(chunk)) {
    if (chunk.empty()) continue;
    text_ = chunk;
    pos_ = 0;
    return true;
  }
  text_ = {};
  pos_ = 0;
  return false;
}

void tokenize(std::string_view line, std::vector<Token>& tokens, Separators separators) {
  tokens.clear();
  if (separators == Separators::blanks)
    split(line, tokens, [](char c) { return c == ' ' || c == '\t'; });
  else
    split(line, tokens, [](char c) { return c == ' ' || c == '\t' || c == '\r'; });
}

std::string quoted(std::string_view token, std::size_t limit) {
  std::string out = "'";
  for (std::size_t i = 0; i < token.size() && i < limit; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    out += (c < 0x20 || c == 0x7F) ? '?' : static_cast<char>(c);
  }
  if (token.size() > limit) out += "...";
  return out + "'";
}

void fail(const std::string& file, std::uint64_t line, std::uint64_t column,
          const std::string& message) {
  throw Error(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message);
}

void fail(const std::string& file, std::uint64_t line, std::uint64_t column, Message message) {
  throw Error(ErrorCode::other, std::move(message))
      .with_context(file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": ");
}

bool is_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  return true;
}

std::optional<std::uint64_t> to_u64(std::string_view s, std::uint64_t max) {
  if (!is_digits(s)) return std::nullopt;
  std::uint64_t value = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || ptr != s.data() + s.size() || value > max) return std::nullopt;
  return value;
}

std::optional<std::int64_t> to_i64(std::string_view s) {
  if (s.empty()) return std::nullopt;
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  if (ec != std::errc() || ptr != s.data() + s.size()) return std::nullopt;
  return value;
}

std::optional<double> to_real(std::string_view s) {
  if (s.empty() || s[0] == '+' || s[0] == 'e' || s[0] == 'E') return std::nullopt;
  // from_chars alone would also take "inf", "nan" and (with chars_format::hex) hex digits.
  if (s.find_first_not_of("0123456789.eE+-") != std::string_view::npos) return std::nullopt;
  double value = 0;
  const auto [ptr, ec] =
      std::from_chars(s.data(), s.data() + s.size(), value, std::chars_format::general);
  if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::string plural(std::uint64_t n, const char* word) {
  const std::string w = word;
  if (n == 1) return "1 " + w;
  return std::to_string(n) + " " + (w == "vertex" ? std::string("vertices") : w + "s");
}

}  // namespace mosb::converters::text
