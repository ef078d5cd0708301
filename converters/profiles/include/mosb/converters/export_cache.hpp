// The export cache (spec/RUN.md §10.3): the text forms solver profiles read, exported once per
// (instance digest, objectives, query set, form, id base, scale, arc handling) into a directory of
// their own under the cache, written whole or not at all (a temporary directory renamed into
// place, so concurrent runs are safe) and reused by later queries and runs. Each file's content
// hash is in the manifest and checked before every use: an entry that does not match (a solver or
// a user edited a file, a file is gone, a link or a FIFO stands in its place) is exported again.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

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
// from `cache`, made there first when missing or damaged (said through the warning handler).
// Throws mosb::Error naming the file concerned.
CachedExport cached_export(const std::filesystem::path& cache,
                           const std::filesystem::path& instance, const std::string& digest,
                           const DimacsExportOptions& options);

// Where the one-line notice of a damaged entry goes ("FILE: what was wrong; exported again");
// by default (or given an empty handler) "mosb: warning: LINE" on stderr. Set it before runs.
void set_export_cache_warning_handler(std::function<void(const std::string&)> handler);

struct ClearedExports {
  std::uint64_t removed = 0;      // exports and temporaries of finished runs
  std::vector<std::string> left;  // one line per entry left alone: "PATH: why"
};

// Removes the exports in `cache` (directories named and laid out as cached_export makes them)
// and the temporaries of runs no longer alive; nothing else, and no symlink is followed.
ClearedExports clear_export_cache(const std::filesystem::path& cache);

}  // namespace mosb::converters
