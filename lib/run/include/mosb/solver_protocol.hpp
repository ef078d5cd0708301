// The solver protocol of `mosb run` (spec/RUN.md §3): what a solver prints for one query. The
// front is one cost vector per line (whitespace-separated decimal numbers, vectors in any order)
// on standard output or in the {front} file; statistics are `mosb: key=value` lines on standard
// error. Both parsers take the text in chunks of any size (a solver's output is read a chunk at a
// time, so mosb holds no more of it than the parsed values), and are pure functions of the text,
// so the fuzz target and the unit tests call them directly.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mosb {

struct ProtocolFront {
  std::vector<double> costs;  // vector after vector, `objectives` values each
  std::uint64_t vectors = 0;
};

// A front: lines end in "\n" (a "\r" before it is ignored, the last line may lack it); blank
// lines are skipped; every other line holds exactly `objectives` finite numbers separated by
// blanks or tabs. A value of an integer objective (`integer[i]`) is an unsigned decimal integer
// of digits alone, at most 2^53, read exactly (9007199254740993 is refused, not rounded); a value
// of a float objective is a decimal number as std::from_chars reads it (sign, fraction,
// exponent). Errors are mosb::Error "NAME:LINE:COLUMN: message".
class ProtocolFrontParser {
 public:
  // `integer` has one entry per objective (empty: every objective is a float one). A front of more
  // than `max_values` values is refused ("more than N values").
  ProtocolFrontParser(std::size_t objectives, std::vector<bool> integer, std::string name,
                      std::uint64_t max_values = UINT64_MAX);
  void feed(std::string_view chunk);  // any split of the text
  ProtocolFront finish();             // the last line, then the front

 private:
  void parse_line(std::string_view line);
  std::size_t objectives_;
  std::vector<bool> integer_;
  std::string name_;
  std::uint64_t max_values_;
  std::uint64_t line_ = 0;
  std::string partial_;  // an unfinished line (at most one line's bytes)
  ProtocolFront front_;
};

// The whole front of `text` at once (ProtocolFrontParser over one chunk).
ProtocolFront parse_protocol_front(std::string_view text, std::size_t objectives,
                                   const std::string& name, const std::vector<bool>& integer = {});

// What a solver reported on standard error. Lines starting with "mosb: " hold one key=value each;
// known keys: expanded, generated (unsigned integers, below 2^64 - 1), runtime_seconds (a finite
// number >= 0). Other keys are ignored, as spec/RUN.md says, and not kept: mosb's memory does not
// grow with what a solver prints. Other lines are the solver's own messages and ignored.
struct ReportedStatistics {
  std::optional<std::uint64_t> expanded, generated;
  std::optional<double> runtime_seconds;
};

// Errors are mosb::Error "NAME:LINE: message" on a `mosb: ` line that is not key=value or a known
// key with a malformed value. Only `mosb: ` lines are kept (at most 4 KiB each), whatever the
// solver prints besides.
class ProtocolStatisticsParser {
 public:
  explicit ProtocolStatisticsParser(std::string name);
  void feed(std::string_view chunk);
  ReportedStatistics finish();

 private:
  void parse_line(std::string_view line);
  std::string name_;
  std::uint64_t line_ = 0;
  std::string partial_;
  bool skipping_ = false;  // the current line is too long to be a `mosb: ` line: skipped
  ReportedStatistics stats_;
};

ReportedStatistics parse_protocol_statistics(std::string_view text, const std::string& name);

}  // namespace mosb
