// The export cache (spec/RUN.md §10.3): the text forms solver profiles read, exported once per
// (instance digest, objectives, query set, form, id base, scale, arc handling) into a directory of
// their own under the cache, written whole or not at all (a temporary directory renamed into
// place, so concurrent runs are safe) and reused by later queries and runs.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "mosb/converters/dimacs_export.hpp"

namespace mosb::converters {

// $MOSB_EXPORT_CACHE, else $XDG_CACHE_HOME/mosb/exports, else $HOME/.cache/mosb/exports.
std::filesystem::path default_export_cache();

struct CachedExport {
  DimacsExportFiles files;
  std::filesystem::path directory;
  bool reused = false;  // found in the cache, nothing written
};

// The export of `instance` (whose content digest is `digest`) with `options` (out_dir is ignored)
// from `cache`, made there first when missing. Throws mosb::Error naming the file concerned.
CachedExport cached_export(const std::filesystem::path& cache,
                           const std::filesystem::path& instance, const std::string& digest,
                           const DimacsExportOptions& options);

// Removes every export in `cache` (and temporaries left by killed runs); the number removed.
std::uint64_t clear_export_cache(const std::filesystem::path& cache);

}  // namespace mosb::converters
