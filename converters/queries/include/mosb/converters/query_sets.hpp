// Query sets added to an existing instance (spec/QUERIES.md): pairs imported from a text file or
// drawn at random, and the `queries.<set>.*` metadata keys that record where each set came from.
// The caller writes the result with rewrite_instance (in place or to a new file).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/metadata.hpp"

namespace mosb::converters {

// The instance's new metadata and the query set to add or replace.
struct QuerySetEdit {
  Metadata metadata;
  QuerySet set;
  std::vector<std::string> bound_views;  // the views whose query set the new set became
};

// Which views a new query set becomes the query set of (spec/QUERIES.md, "Views"): `view` alone
// when given (it must exist; a query set it had is replaced), else every view that has none yet,
// except one its converter meant for another set (`source.param.view.NAME = OBJ,...@OTHER`).
struct ViewBinding {
  std::optional<std::string> view;
};

struct QueryImportOptions {
  std::filesystem::path file;  // plain or compressed query text
  std::optional<unsigned>
      id_base;  // of the ids in `file`; default: the instance's metadata id_base
  std::optional<std::string> match;  // keep only `graph s t` lines whose graph field contains it
  // `file` is a Moving AI scenario (spec/families/games.md §4) of the map the instance was built
  // from (vertex data `cell`, metadata map.width and map.height): its rows become the set, with
  // each `optimal` as the set's reference for `length` (spec/SOLUTIONS.md §6). Excludes id_base and
  // match.
  bool scenario = false;
  ViewBinding binding;
};

struct QueryDrawOptions {
  std::uint64_t count = 100;
  std::uint64_t seed = 1;
  bool allow_same = false;  // keep start = goal pairs (redrawn otherwise)
  ViewBinding binding;
};

// The most pairs one `draw` may ask for (800 MB of pairs).
inline constexpr std::uint64_t kMaxDrawnQueries = 100'000'000;

// Both throw mosb::Error naming `instance` (or the query file); a set named `set` that exists
// already is refused unless `replace`.
QuerySetEdit import_query_set(const GraphReader& instance, const std::string& set,
                              const QueryImportOptions& options, bool replace);
QuerySetEdit draw_query_set(const GraphReader& instance, const std::string& set,
                            const QueryDrawOptions& options, bool replace);

}  // namespace mosb::converters
