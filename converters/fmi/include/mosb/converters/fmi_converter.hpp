// FMI / OsmGraphCreator text road graphs (GER_10, spec/families/ger.md) into a GraphInput, with the
// paper's breadth-first extraction of a connected subgraph. Every input error is one line
// "FILE:LINE:COLUMN: message".
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "mosb/converters/objective.hpp"
#include "mosb/converters/text_scan.hpp"
#include "mosb/graph_builder.hpp"

namespace mosb::converters {

// One parsed FMI file; vertex ids 0-based.
struct FmiGraph {
  std::uint64_t vertex_count = 0;
  std::vector<std::uint64_t> osm_ids;
  std::vector<double> coords;  // lat, lon interleaved
  // Integers, or reals when any elevation has '.' or an exponent.
  std::variant<std::vector<std::int64_t>, std::vector<double>> elevation;
  std::vector<std::uint32_t> tails;
  std::vector<std::uint32_t> heads;
  // One entry per cost column: integers, or reals when any value in the column has '.' or an
  // exponent.
  std::vector<std::variant<std::vector<std::uint64_t>, std::vector<double>>> costs;
  std::vector<std::uint64_t> types;      // standard layout only
  std::vector<std::uint64_t> maxspeeds;  // standard layout with the maxspeed field only
};

// `cost_count` empty: the standard layout `src trg cost type [maxspeed]`; D: `src trg c1 .. cD`,
// and with `ignore_extra_fields` further fields (the same number on every edge line) are skipped.
FmiGraph parse_fmi(std::string_view text, const std::string& display_name,
                   std::optional<unsigned> cost_count, bool ignore_extra_fields = false);
// The same over text in chunks; `size_hint` (the text's size or an estimate) bounds reservations.
FmiGraph parse_fmi(text::TextSource& source, std::uint64_t size_hint,
                   const std::string& display_name, std::optional<unsigned> cost_count,
                   bool ignore_extra_fields = false);

// The first `count` vertices in BFS order from `root` (along out-arcs, or along arcs in both
// directions when `undirected`; neighbours in file order), sorted by id. Throws mosb::Error naming
// `display_name` when `root` is no vertex or fewer than `count` vertices are reachable.
std::vector<std::uint32_t> bfs_select(const FmiGraph& graph, std::uint32_t root,
                                      std::uint64_t count, bool undirected,
                                      const std::string& display_name);

// Keeps the vertices `selected` (sorted ids; new id = rank) and the arcs between them, in file
// order.
FmiGraph induced_subgraph(const FmiGraph& graph, const std::vector<std::uint32_t>& selected);

struct FmiBfs {
  std::uint32_t root = 0;
  std::uint64_t count = 0;
  bool undirected = false;
};

struct FmiOptions {
  std::string file;
  std::optional<unsigned> cost_count;  // --costs D
  bool ignore_extra_fields = false;    // with --costs: skip fields after the D costs
  std::vector<Objective> objectives;   // empty: GER_10 names for D = 10, else c1..cd
  std::optional<FmiBfs> extract_bfs;
  std::optional<std::string> name;  // benchmark; default: the file's base name without extensions
  Progress progress;                // stage "read": raw bytes parsed so far
};

// The GER_10 objective names in the paper's order.
const std::vector<std::string>& ger10_objective_names();

// Reads (decompressing as needed) and converts; throws mosb::Error.
GraphInput convert_fmi(const FmiOptions& options);

}  // namespace mosb::converters
