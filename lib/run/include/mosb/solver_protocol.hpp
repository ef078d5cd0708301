// The solver protocol of `mosb run` (spec/RUN.md §3): what a solver prints for one query. The
// front is one cost vector per line (whitespace-separated decimal numbers, vectors in any order)
// on standard output or in the {front} file; statistics are `mosb: key=value` lines on standard
// error. Both parsers are pure functions of the text, so the fuzz target and the unit tests call
// them directly.
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

// Parses a front: lines end in "\n" (a "\r" before it is ignored, the last line may lack it);
// blank lines are skipped; every other line holds exactly `objectives` finite numbers (as
// std::from_chars reads them: decimal, optional sign, fraction and exponent) separated by blanks
// or tabs. Throws mosb::Error "NAME:LINE:COLUMN: message" on anything else.
ProtocolFront parse_protocol_front(std::string_view text, std::size_t objectives,
                                   const std::string& name);

// What a solver reported on standard error. Lines starting with "mosb: " hold one key=value each;
// known keys: expanded, generated (unsigned integers), runtime_seconds (a finite number >= 0).
// Other keys are kept in `other` (spec/RUN.md says they are ignored); other lines are the
// solver's own messages and ignored.
struct ReportedStatistics {
  std::optional<std::uint64_t> expanded, generated;
  std::optional<double> runtime_seconds;
  std::vector<std::pair<std::string, std::string>> other;
};

// Throws mosb::Error "NAME:LINE: message" on a `mosb: ` line that is not key=value or a known
// key with a malformed value.
ReportedStatistics parse_protocol_statistics(std::string_view text, const std::string& name);

}  // namespace mosb
