// DIMACS shortest-path graphs (.gr, one or several cost columns per arc line; optional .co
// coordinates) into a GraphInput. Every input error is one line "FILE:LINE:COLUMN: message".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mosb/converters/objective.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/format.hpp"
#include "mosb/graph_builder.hpp"

namespace mosb::converters {

// One parsed .gr file; vertex ids 0-based.
struct DimacsGraph {
  std::uint64_t vertex_count = 0;
  std::vector<std::uint32_t> tails;
  std::vector<std::uint32_t> heads;
  // 1-based line number of each arc, when asked for (the message of a later file that disagrees
  // cites the line of this file's arc; convert_dimacs finds it by scanning the file again instead).
  std::vector<std::uint64_t> arc_lines;
  // One entry per cost column: integers, or reals when any value in the column has '.' or an
  // exponent.
  std::vector<std::variant<std::vector<std::uint64_t>, std::vector<double>>> columns;
};

// Arcs another file must match, in order (per-objective files). `graph` needs its arc_lines.
struct DimacsReference {
  const std::string* display_name;
  const DimacsGraph* graph;
};

// Parses .gr text. `id_base` is 0 or 1. The declared vertex count is checked against physical
// memory (check_declared_vertices); the declared arc count reserves no more than `size_hint` (the
// text's size, or an estimate) could hold. The text comes whole, or in chunks from a TextSource.
DimacsGraph parse_dimacs_gr(std::string_view text, const std::string& display_name,
                            unsigned id_base, const DimacsReference* reference = nullptr);
DimacsGraph parse_dimacs_gr(text::TextSource& source, std::uint64_t size_hint,
                            const std::string& display_name, unsigned id_base,
                            const DimacsReference* reference = nullptr,
                            bool record_arc_lines = true);

// Line numbers of the arc lines of .gr text that parses.
std::vector<std::uint64_t> dimacs_arc_lines(text::TextSource& source);

// Parses .co text: `p aux sp co n`, then one `v id x y` per vertex (integers). x, y interleaved.
std::vector<std::int64_t> parse_dimacs_co(std::string_view text, const std::string& display_name,
                                          unsigned id_base, std::uint64_t vertex_count);
std::vector<std::int64_t> parse_dimacs_co(text::TextSource& source, const std::string& display_name,
                                          unsigned id_base, std::uint64_t vertex_count);

struct DimacsOptions {
  std::vector<std::string> gr_files;
  std::vector<Objective> objectives;  // empty: c1..cd
  std::optional<std::string> co_file;
  std::optional<std::string> name;  // benchmark; default: first file's base name without extensions
  unsigned id_base = 1;
  std::optional<format::ElementType> cost_type;
  Progress progress;  // stage "read": raw bytes of the .gr and .co files parsed so far
};

// Reads (decompressing as needed; several .gr files in parallel, on up to as many threads as the
// machine has cores) and converts; throws mosb::Error.
GraphInput convert_dimacs(const DimacsOptions& options);

}  // namespace mosb::converters
