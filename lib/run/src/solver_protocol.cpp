#include "mosb/solver_protocol.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

#include "mosb/error.hpp"

namespace mosb {

namespace {

// A line of a front is a few dozen bytes per value: one this long is no vector, and holding it
// whole would let a solver grow mosb's memory with one endless line.
constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;
// A statistics line is short; a longer stderr line is the solver's own message.
constexpr std::size_t kMaxStatisticsLine = 4096;
constexpr std::uint64_t kMaxExactInteger = std::uint64_t{1} << 53;

[[noreturn]] void refuse_at(const std::string& name, std::uint64_t line, std::size_t column,
                            const std::string& message) {
  throw Error(name + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + message);
}

std::string shown(const char* begin, const char* end) {
  const std::size_t length = std::min<std::size_t>(static_cast<std::size_t>(end - begin), 24);
  std::string text;
  for (std::size_t i = 0; i < length; ++i) {
    const auto c = static_cast<unsigned char>(begin[i]);
    text += c >= 0x20 && c < 0x7f ? static_cast<char>(c) : '?';
  }
  return text;
}

// Calls each(line) for every complete line of `chunk` (without its "\n" and a "\r" before it),
// keeping an unfinished last line in `partial` for the next chunk. A line longer than `limit`
// calls too_long() once and is skipped to its end (`dropping` carries that across chunks).
template <class Each, class TooLong>
void split_lines(std::string_view chunk, std::string& partial, bool& dropping, std::size_t limit,
                 Each&& each, TooLong&& too_long) {
  while (!chunk.empty()) {
    const std::size_t newline = chunk.find('\n');
    const std::string_view piece = chunk.substr(0, newline);
    if (dropping) {
      if (newline == std::string_view::npos) return;
      dropping = false;
    } else if (partial.size() + piece.size() > limit) {
      too_long();
      partial.clear();
      dropping = true;
      continue;
    } else if (newline == std::string_view::npos) {
      partial.append(piece);
      return;
    } else if (partial.empty()) {
      each(piece.ends_with('\r') ? piece.substr(0, piece.size() - 1) : piece);
    } else {
      partial.append(piece);
      const std::string_view line(partial);
      each(line.ends_with('\r') ? line.substr(0, line.size() - 1) : line);
      partial.clear();
    }
    chunk.remove_prefix(newline + 1);
  }
}

}  // namespace

ProtocolFrontParser::ProtocolFrontParser(std::size_t objectives, std::vector<bool> integer,
                                         std::string name, std::uint64_t max_values)
    : objectives_(objectives),
      integer_(std::move(integer)),
      name_(std::move(name)),
      max_values_(max_values) {
  if (objectives_ == 0) throw Error(name_ + ": no objective");
  integer_.resize(objectives_, false);
}

void ProtocolFrontParser::feed(std::string_view chunk) {
  bool dropping = false;  // never: a line too long is refused
  split_lines(
      chunk, partial_, dropping, kMaxLineBytes,
      [&](std::string_view line) {
        ++line_;
        parse_line(line);
      },
      [&] {
        refuse_at(name_, line_ + 1, 1,
                  "a line longer than " + std::to_string(kMaxLineBytes) + " bytes");
      });
}

ProtocolFront ProtocolFrontParser::finish() {
  if (!partial_.empty()) {
    ++line_;
    std::string_view line(partial_);
    parse_line(line.ends_with('\r') ? line.substr(0, line.size() - 1) : line);
    partial_.clear();
  }
  return std::move(front_);
}

void ProtocolFrontParser::parse_line(std::string_view text) {
  const char* const start = text.data();
  const char* p = start;
  const char* const end = start + text.size();
  const auto column = [&](const char* at) { return static_cast<std::size_t>(at - start) + 1; };
  std::size_t count = 0;
  while (true) {
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    if (p == end) break;
    const char* token_end = p;
    while (token_end < end && *token_end != ' ' && *token_end != '\t') ++token_end;
    if (count == objectives_)
      refuse_at(name_, line_, column(p),
                "more than " + std::to_string(objectives_) + " values in a vector");
    double value = 0;
    if (integer_[count]) {
      std::uint64_t n = 0;
      const auto [next, ec] = std::from_chars(p, token_end, n);
      if (ec == std::errc::result_out_of_range ||
          (ec == std::errc() && next == token_end && n > kMaxExactInteger))
        refuse_at(name_, line_, column(p),
                  "'" + shown(p, token_end) + "' is above 2^53, the largest exact integer cost");
      if (ec != std::errc() || next != token_end)
        refuse_at(name_, line_, column(p),
                  "'" + shown(p, token_end) + "' is not an unsigned integer (objective " +
                      std::to_string(count + 1) + " is an integer one)");
      value = static_cast<double>(n);
    } else {
      const auto [next, ec] = std::from_chars(p, token_end, value);
      if (ec != std::errc() || next != token_end)
        refuse_at(name_, line_, column(p), "'" + shown(p, token_end) + "' is not a number");
      if (!std::isfinite(value)) refuse_at(name_, line_, column(p), "a cost is not finite");
    }
    if (front_.costs.size() >= max_values_)
      refuse_at(name_, line_, column(p),
                "more than " + std::to_string(max_values_) + " values (the output limit)");
    front_.costs.push_back(value);
    ++count;
    p = token_end;
  }
  if (count != 0 && count != objectives_)
    refuse_at(name_, line_, column(end),
              std::to_string(count) + " values, the view has " + std::to_string(objectives_) +
                  " objectives");
  if (count != 0) ++front_.vectors;
}

ProtocolFront parse_protocol_front(std::string_view text, std::size_t objectives,
                                   const std::string& name, const std::vector<bool>& integer) {
  ProtocolFrontParser parser(objectives, integer, name);
  parser.feed(text);
  return parser.finish();
}

namespace {

std::uint64_t parse_count(std::string_view value, const std::string& name, std::uint64_t line,
                          std::string_view key) {
  std::uint64_t n = 0;
  const auto [next, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
  // 2^64 - 1 is a solution file's "absent": no count a solver reports.
  if (value.empty() || ec != std::errc() || next != value.data() + value.size() || n == UINT64_MAX)
    throw Error(name + ":" + std::to_string(line) + ": " + std::string(key) +
                " is not an unsigned integer below 2^64 - 1");
  return n;
}

double parse_seconds(std::string_view value, const std::string& name, std::uint64_t line) {
  double x = 0;
  const auto [next, ec] = std::from_chars(value.data(), value.data() + value.size(), x);
  if (value.empty() || ec != std::errc() || next != value.data() + value.size() ||
      !std::isfinite(x) || x < 0)
    throw Error(name + ":" + std::to_string(line) +
                ": runtime_seconds is not a finite number of seconds >= 0");
  return x;
}

}  // namespace

ProtocolStatisticsParser::ProtocolStatisticsParser(std::string name) : name_(std::move(name)) {}

void ProtocolStatisticsParser::feed(std::string_view chunk) {
  split_lines(
      chunk, partial_, skipping_, kMaxStatisticsLine,
      [&](std::string_view line) {
        ++line_;
        parse_line(line);
      },
      [&] { ++line_; });
}

ReportedStatistics ProtocolStatisticsParser::finish() {
  if (!partial_.empty() && !skipping_) {
    ++line_;
    parse_line(partial_);
  }
  partial_.clear();
  return stats_;
}

void ProtocolStatisticsParser::parse_line(std::string_view content) {
  static constexpr std::string_view prefix = "mosb: ";
  if (!content.starts_with(prefix)) return;
  content.remove_prefix(prefix.size());
  const std::size_t equals = content.find('=');
  if (equals == 0 || equals == std::string_view::npos)
    throw Error(name_ + ":" + std::to_string(line_) + ": a 'mosb: ' line without key=value");
  const std::string_view key = content.substr(0, equals), value = content.substr(equals + 1);
  if (key == "expanded")
    stats_.expanded = parse_count(value, name_, line_, key);
  else if (key == "generated")
    stats_.generated = parse_count(value, name_, line_, key);
  else if (key == "runtime_seconds")
    stats_.runtime_seconds = parse_seconds(value, name_, line_);
}

ReportedStatistics parse_protocol_statistics(std::string_view text, const std::string& name) {
  ProtocolStatisticsParser parser(name);
  parser.feed(text);
  return parser.finish();
}

}  // namespace mosb
