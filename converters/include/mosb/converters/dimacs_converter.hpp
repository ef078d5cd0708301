// DIMACS shortest-path graphs (.gr, one or several cost columns per arc line; optional .co
// coordinates) into a GraphInput. Every input error is one line "FILE:LINE:COLUMN: message".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mosb/format.hpp"
#include "mosb/converters/objective.hpp"
#include "mosb/graph_builder.hpp"

namespace mosb::converters {

// One parsed .gr file; vertex ids 0-based.
struct DimacsGraph {
  std::uint64_t vertex_count = 0;
  std::vector<std::uint32_t> tails;
  std::vector<std::uint32_t> heads;
  std::vector<std::uint64_t> arc_lines;  // 1-based line number of each arc
  // One entry per cost column: integers, or reals when any value in the column has '.' or an exponent.
  std::vector<std::variant<std::vector<std::uint64_t>, std::vector<double>>> columns;
};

// Arcs another file must match, in order (per-objective files).
struct DimacsReference {
  const std::string* display_name;
  const DimacsGraph* graph;
};

// Parses .gr text held in memory. `id_base` is 0 or 1.
DimacsGraph parse_dimacs_gr(std::string_view text, const std::string& display_name,
                            unsigned id_base, const DimacsReference* reference = nullptr);

// Parses .co text: `p aux sp co n`, then one `v id x y` per vertex (integers). x, y interleaved.
std::vector<std::int64_t> parse_dimacs_co(std::string_view text, const std::string& display_name,
                                          unsigned id_base, std::uint64_t vertex_count);

struct DimacsOptions {
  std::vector<std::string> gr_files;
  std::vector<Objective> objectives;  // empty: c1..cd
  std::optional<std::string> co_file;
  std::optional<std::string> name;    // benchmark; default: first file's base name without extensions
  unsigned id_base = 1;
  std::optional<format::ElementType> cost_type;
};

// Reads (decompressing as needed) and converts; throws mosb::Error.
GraphInput convert_dimacs(const DimacsOptions& options);

}  // namespace mosb::converters
