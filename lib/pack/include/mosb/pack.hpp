// The packed form of a mosb file (spec/FORMAT.md §6 "Packed files"): every non-empty section but
// the metadata whose bytes shrink is stored as one zstd frame in the same container; the section
// table stays uncompressed, so the header, the table and the §8 content digest read the same as
// unpacked.
//
// Unpacking restores the layout of mosb::FileWriter, the canonical one (sections in table order,
// each at the next 64-byte boundary, zero padding, the table last), which is recomputed from the
// table alone. pack_file therefore refuses an input whose layout is not canonical: its exact bytes
// could not be restored. Packing is deterministic: a fixed level, no timestamps, no dictionary, one
// single-threaded zstd context per section (so any thread count gives the same bytes).
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

#include "mosb/container.hpp"
#include "mosb/format.hpp"
#include "mosb/graph_reader.hpp"

namespace mosb {

struct PackOptions {
  int level = 19;        // zstd compression level, 1..22
  unsigned threads = 1;  // sections compressed at once; does not change the output bytes
  // Store no reverse CSR section that is the transpose of the forward CSR (encoding transpose,
  // format 1.2): unpacking derives the sections again. About a third of a packed NetMaker file.
  bool derive_reverse = true;
};

// Writes the packed form of the instance `in` (packed or not) to `out`, atomically
// (mosb::AtomicFile: `out` shows the old file or the complete new one). Every frame is decoded
// again and compared before the file is committed. `out` may be `in` itself (an in-place rewrite);
// the CLI allows that only with --in-place. Throws mosb::Error naming the file.
void pack_file(const std::filesystem::path& in, const std::filesystem::path& out,
               const PackOptions& options);

// Writes the unpacked form of `in` to `out`, atomically, after checking every section's checksum:
// byte-identical to the file that was packed. An unpacked input is rewritten in canonical layout.
void unpack_file(const std::filesystem::path& in, const std::filesystem::path& out);

// The unpacked form of a container in memory (64-byte aligned, owned by the result), each section
// decoded and its checksum checked. Hostile input is refused with "DISPLAY_NAME: section 'S': ..."
// before any allocation larger than the decoded lengths the table declares, which are bounded by
// what each stored frame can hold at zstd's maximum ratio.
MappedFile unpack_bytes(std::span<const std::byte> bytes, std::string_view display_name);

// Opens an instance whether packed or not: a packed file (§6) is decoded into owned, 64-byte
// aligned memory (every section's checksum checked on the way) instead of being refused as
// GraphReader::open refuses it; an unpacked file is mapped as by GraphReader::open. The accessors
// then work the same on both. With `level`, runs verify(reader, level) as GraphReader::open does.
GraphReader load(const std::filesystem::path& path);
GraphReader load(const std::filesystem::path& path, VerifyLevel level);

}  // namespace mosb
