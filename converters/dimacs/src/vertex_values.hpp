// The DIMACS auxiliary files of per-vertex integers, one parser for both: the .co coordinates
// (parse_dimacs_co) and the elevations of DIMACS-Extended (parse_dimacs_elevation). `c` comments,
// one `p aux sp TAG n` line, then one `v id value...` line per vertex; errors are
// "FILE:LINE:COLUMN: message".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mosb/converters/text_scan.hpp"

namespace mosb::converters {

// What tells one such file from the other, in its contents and its messages.
struct VertexValueFile {
  const char* tag;         // the header is 'p aux sp TAG n'
  std::size_t values;      // integers per vertex, interleaved in the result
  const char* value_name;  // "expected an integer NAME, found ..."
  const char* line_rule;   // "missing field: RULE", "extra field 'x': RULE"
  // Wording the two parsers had apart before they were one, kept byte for byte:
  const char* header_cited_by_v;  // "'v' line before the HEADER line"
  // Ids and the count: a field that is not digits told from a number out of range, and "declares
  // 1 vertex". Without it, "vertex id 'x' outside 1..n", "expected the vertex count, found 'x'"
  // for both, and "declares 1 vertices".
  bool precise_field_errors;
};

inline constexpr VertexValueFile kCoordinateFile{
    "co", 2, "coordinate", "a coordinate line is 'v id x y'", "'p aux sp co'", true};
inline constexpr VertexValueFile kElevationFile{
    "elev", 1, "elevation", "an elevation line is 'v id elevation'", "'p aux sp elev n'", false};

// The values of vertices 0..vertex_count-1 (ids in the file count from `id_base`), `file.values`
// per vertex; the header must declare `vertex_count` vertices and each must have one 'v' line.
std::vector<std::int64_t> parse_vertex_values(text::LineScanner& lines,
                                              const std::string& display_name, unsigned id_base,
                                              std::uint64_t vertex_count,
                                              const VertexValueFile& file);

}  // namespace mosb::converters
