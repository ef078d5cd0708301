// Rewrites an existing instance with new metadata and some query sets added or replaced, copying
// every other section's bytes unchanged (so their checksums, and the graph, stay identical).
#pragma once

#include <filesystem>
#include <vector>

#include "mosb/graph_builder.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/metadata.hpp"

namespace mosb {

// Writes `output` atomically: the sections of `source` in table order, the metadata section
// replaced by `metadata`, a `queries` section whose name is in `query_sets` replaced in place, the
// other `query_sets` appended at the end in the given order; a replaced set's old
// `query_reference` section is dropped, and a set with a reference gets its section and metadata
// keys (write_query_set, add_reference_metadata). `output` may be the file `source`
// maps: the new file is renamed over it, and the mapping stays valid until `source` is destroyed;
// such an in-place rewrite keeps the file's mode, writes through a symlink, and refuses read-only
// and multiply hard-linked files (AtomicFile::Existing::rewrite_in_place).
// Refuses packed (zstd) sources, copied sections whose bytes do not match their checksum, query
// endpoints not below n and metadata views naming missing sections; throws mosb::Error.
void rewrite_instance(const GraphReader& source, const Metadata& metadata,
                      const std::vector<QuerySet>& query_sets, const std::filesystem::path& output);

}  // namespace mosb
