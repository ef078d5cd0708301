#include "mosb/solver_protocol.hpp"

#include <charconv>
#include <cmath>
#include <cstring>

#include "mosb/error.hpp"

namespace mosb {

namespace {

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

// Parses one line [p, end) of a front into `out`; returns the number of values (0: blank line).
std::size_t parse_line(const char* p, const char* end, const char* line_start,
                       std::size_t objectives, std::vector<double>& out, const std::string& name,
                       std::uint64_t line) {
  std::size_t count = 0;
  const auto column = [&](const char* at) { return static_cast<std::size_t>(at - line_start) + 1; };
  while (true) {
    while (p < end && (*p == ' ' || *p == '\t')) ++p;
    if (p == end) break;
    double value = 0;
    const auto [next, ec] = std::from_chars(p, end, value);
    if (ec != std::errc() || (next < end && *next != ' ' && *next != '\t'))
      refuse_at(name, line, column(p), "'" + shown(p, end) + "' is not a number");
    if (!std::isfinite(value)) refuse_at(name, line, column(p), "a cost is not finite");
    if (++count > objectives)
      refuse_at(name, line, column(p),
                "more than " + std::to_string(objectives) + " values in a vector");
    out.push_back(value);
    p = next;
  }
  if (count != 0 && count != objectives)
    refuse_at(name, line, column(end),
              std::to_string(count) + " values, the view has " + std::to_string(objectives) +
                  " objectives");
  return count;
}

}  // namespace

ProtocolFront parse_protocol_front(std::string_view text, std::size_t objectives,
                                   const std::string& name) {
  ProtocolFront front;
  if (objectives == 0) throw Error(name + ": no objective");
  const char* p = text.data();
  const char* const end = p + text.size();
  std::uint64_t line = 0;
  while (p < end) {
    ++line;
    const char* newline = static_cast<const char*>(std::memchr(p, '\n', end - p));
    const char* line_end = newline ? newline : end;
    const char* content_end = line_end > p && line_end[-1] == '\r' ? line_end - 1 : line_end;
    if (parse_line(p, content_end, p, objectives, front.costs, name, line) != 0) ++front.vectors;
    p = newline ? newline + 1 : end;
  }
  return front;
}

namespace {

std::uint64_t parse_count(std::string_view value, const std::string& name, std::uint64_t line,
                          std::string_view key) {
  std::uint64_t n = 0;
  const auto [next, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
  if (value.empty() || ec != std::errc() || next != value.data() + value.size())
    throw Error(name + ":" + std::to_string(line) + ": " + std::string(key) +
                " is not an unsigned integer");
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

ReportedStatistics parse_protocol_statistics(std::string_view text, const std::string& name) {
  static constexpr std::string_view prefix = "mosb: ";
  ReportedStatistics stats;
  std::uint64_t line = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    ++line;
    std::size_t newline = text.find('\n', pos);
    if (newline == std::string_view::npos) newline = text.size();
    std::string_view content = text.substr(pos, newline - pos);
    pos = newline + 1;
    if (!content.empty() && content.back() == '\r') content.remove_suffix(1);
    if (!content.starts_with(prefix)) continue;
    content.remove_prefix(prefix.size());
    const std::size_t equals = content.find('=');
    if (equals == 0 || equals == std::string_view::npos)
      throw Error(name + ":" + std::to_string(line) + ": a 'mosb: ' line without key=value");
    const std::string_view key = content.substr(0, equals), value = content.substr(equals + 1);
    if (key == "expanded")
      stats.expanded = parse_count(value, name, line, key);
    else if (key == "generated")
      stats.generated = parse_count(value, name, line, key);
    else if (key == "runtime_seconds")
      stats.runtime_seconds = parse_seconds(value, name, line);
    else
      stats.other.emplace_back(key, value);
  }
  return stats;
}

}  // namespace mosb
