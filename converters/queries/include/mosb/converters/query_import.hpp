// Query files in the formats in circulation (spec/QUERIES.md): one (start, goal) pair per line as
// `s t`, `s, t` or `s; t`, or targeted-MOSP `.inst` lines `graph-path s t`; `#` and `c` comment
// lines, blank lines, CRLF. Every input error is one line "FILE:LINE:COLUMN: message".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/converters/text_scan.hpp"
#include "mosb/query.hpp"

namespace mosb::converters {

struct QueryFileOptions {
  unsigned id_base = 0;              // base of the ids in the file: 0 or 1
  std::uint64_t vertex_count = 0;    // n: ids must lie in [id_base, n - 1 + id_base]
  std::optional<std::string> match;  // keep only `graph s t` lines whose graph field contains it
};

// Parses query text held in memory; `display_name` stands for the file in messages. Returns the
// selected pairs, 0-based, in file order. Throws mosb::Error.
std::vector<Query> parse_query_file(std::string_view text, const std::string& display_name,
                                    const QueryFileOptions& options);
// The same over text in chunks (an InputFile).
std::vector<Query> parse_query_file(text::TextSource& source, const std::string& display_name,
                                    const QueryFileOptions& options);

}  // namespace mosb::converters
