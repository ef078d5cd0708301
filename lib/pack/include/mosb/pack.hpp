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

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "mosb/container.hpp"
#include "mosb/format.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/progress.hpp"

namespace mosb {

struct PackOptions {
  int level = 19;        // zstd compression level, 1..22
  unsigned threads = 1;  // sections compressed at once; does not change the output bytes
  // Store no reverse CSR section that is the transpose of the forward CSR (encoding transpose,
  // format 1.2): unpacking derives the sections again. About a third of a packed NetMaker file.
  bool derive_reverse = true;
  // The most memory decoding the input (and the packed result, to verify it) may take; 0: the
  // available_memory() (see unpack_bytes).
  std::uint64_t max_memory = 0;
};

// The memory decoding a packed file may take when the caller gives no cap (max_memory 0 below):
// what the system reports available (Linux: MemAvailable in /proc/meminfo; elsewhere
// sysconf(_SC_AVPHYS_PAGES) pages).
std::uint64_t available_memory();

// Writes the packed form of the instance or solution file `in` (packed or not) to `out`,
// atomically (mosb::AtomicFile: `out` shows the old file or the complete new one), and returns
// its §8 content digest (the input's). The input is checked first: an instance as verify does at
// level full (checksums, structure, the padding of a packed input), a solution file's checksums
// and padding (its fronts are SolutionReader's to check, at every open); a damaged input is
// refused, not repaired. A solution file must be of 1.3 or later and state the minor its content
// gives (format::solution_layout_minor); packed, it says 1.6 (spec/SOLUTIONS.md §1). The packed
// file must unpack to the input's bytes before it is committed. `out` may be `in` itself (an
// in-place rewrite); the CLI allows that only with --in-place. Throws mosb::Error naming the file;
// `out` is then untouched.
std::string pack_file(const std::filesystem::path& in, const std::filesystem::path& out,
                      const PackOptions& options);

// Writes the unpacked form of `in` to `out`, atomically, after checking every section's checksum
// and the padding of a packed input (and an instance's structure: verify at level full), and
// returns its content digest: byte-identical to the file that was packed. An unpacked input is
// rewritten in canonical layout. Throws mosb::Error naming `in`; `out` is then untouched.
std::string unpack_file(const std::filesystem::path& in, const std::filesystem::path& out,
                        std::uint64_t max_memory = 0);

// The unpacked form of a container in memory (64-byte aligned, owned by the result), each section
// decoded and its checksum checked. Hostile input is refused with "DISPLAY_NAME: ..." before any
// allocation: each frame must declare its content size, equal to the length the table gives its
// section; an instance's lengths must be the ones the header's counts give each section
// (GraphReader's checks), a packed solution file must say 1.6 or later and derive nothing; and all
// the memory decoding takes must fit in `max_memory` bytes (0: the available_memory()). A packed
// solution file unpacks to the minor format::solution_layout_minor gives its content. `bytes` must
// be 8-byte aligned (a mapping is).
MappedFile unpack_bytes(std::span<const std::byte> bytes, std::string_view display_name,
                        std::uint64_t max_memory = 0);

// Opens an instance whether packed or not: a packed file (§6) is decoded into owned, 64-byte
// aligned memory (every section's checksum checked on the way, within `max_memory` as
// unpack_bytes) instead of being refused as GraphReader::open refuses it; an unpacked file is
// mapped as by GraphReader::open. The accessors then work the same on both. With `level`, runs
// verify(reader, level) as GraphReader::open does.
GraphReader load(const std::filesystem::path& path, std::uint64_t max_memory = 0);
GraphReader load(const std::filesystem::path& path, VerifyLevel level,
                 std::uint64_t max_memory = 0);

// What verify_file found: the first problem (as verify() words it) or none, and the §8 digest.
struct FileVerification {
  std::optional<std::string> problem;
  std::string digest;
  std::uint64_t spilled = 0;  // verify_file_streaming: the bytes its spill file grew to
};

// verify(level) of the instance at `path`, packed or not. Level header reads the header and the
// section table alone, and decodes nothing. The other levels decode a packed file as load() does
// (within `max_memory`) and verify the result; at structure and full, a packed file's own padding
// (§1: every byte outside its frames is zero) is checked too. Throws mosb::Error naming the file
// when it cannot be opened or decoded.
FileVerification verify_file(const std::filesystem::path& path, VerifyLevel level,
                             std::uint64_t max_memory = 0, const Progress& progress = {});

// Memory one streaming check leaves to the next: checks given the same workspace take their large
// buffers from it, mapped and faulted in once, instead of mapping their own (for a pull of many
// files, a third of the check's time). Between checks it keeps at most 64 MiB, until destroyed.
// One check at a time.
class VerifyWorkspace {
 public:
  VerifyWorkspace();
  ~VerifyWorkspace();
  VerifyWorkspace(const VerifyWorkspace&) = delete;
  VerifyWorkspace& operator=(const VerifyWorkspace&) = delete;
  struct Blocks;

 private:
  friend FileVerification verify_file_streaming(const std::filesystem::path&,
                                                const struct StreamingVerifyOptions&);
  std::unique_ptr<Blocks> blocks_;
};

// The disk a streaming check's spill file may take when the caller sets no limit: 64 bytes per
// byte of the file checked, or 8 per byte of the check's memory, whichever is more. Measured
// (spec/MANIFEST.md): a packed Grid needs 14 times its size, a NetMaker 5, a Moving AI map of
// random obstacles 31, at any memory from 4 KiB; and no disk at all in the default 32 MiB. Files
// more regular than any factor could allow for (Moving AI maps of few obstacles pack 190 to 6300
// times smaller) pass on the memory term from 8 MiB up. A file built to need more (5,632 bytes
// whose arcs all repeat one pair, 480 MB of spill) is refused before the check spills a byte.
inline constexpr std::uint64_t kCheckDiskPerFileByte = 64;
inline constexpr std::uint64_t kCheckDiskPerMemoryByte = 8;
inline std::uint64_t default_check_disk(std::uint64_t file_size, std::uint64_t memory) {
  const auto times = [](std::uint64_t bytes, std::uint64_t factor) {
    return bytes > UINT64_MAX / factor ? UINT64_MAX : bytes * factor;
  };
  return std::max(times(file_size, kCheckDiskPerFileByte), times(memory, kCheckDiskPerMemoryByte));
}

// verify_file at level full, in working memory that does not grow with the file: every section is
// read once, front to back, a chunk at a time (a raw one from the mapping, each page let go once
// read; a frame whole when small, else through a streaming zstd decoder; a large shuffled or delta
// frame's content held in a spill file), and the reverse CSR is checked against the transpose of
// the forward CSR, built in memory when both fit `memory`, else in buckets of heads spilled to the
// spill file and sorted one at a time. What it finds is what verify_file finds at level full (a
// problem, or a mosb::Error for a frame that does not decode, naming the file), with the messages
// of verify where the rule is the same. It runs on one thread. Used where files are taken in:
// `store add`, `store pull`.
//
// The spill file never grows past streaming_spill_bound(); when that is more than `disk`, the
// check throws mosb::Error (ErrorCode::no_memory) saying both, before it writes anything.
struct StreamingVerifyOptions {
  std::uint64_t memory = std::uint64_t{32} << 20;  // the working memory aimed at (at least 4 KiB)
  // Where the spill file goes (O_TMPFILE: it has no name and is gone when the check ends, even by
  // kill -9). Empty, or when it cannot be written: the file's own directory, $TMPDIR, /tmp.
  std::filesystem::path scratch_directory;
  VerifyWorkspace* workspace = nullptr;  // none: each check maps its own buffers
  // The most bytes the spill file may take; nullopt: default_check_disk(the file's size, memory).
  std::optional<std::uint64_t> disk = std::nullopt;
};
FileVerification verify_file_streaming(const std::filesystem::path& path,
                                       const StreamingVerifyOptions& options = {});

// The most bytes verify_file_streaming's spill file takes for `reader`'s file in `memory` bytes of
// memory, from its header and section table alone: 12 per arc when the forward CSR and its
// transpose do not fit the memory (16 (n + 1) + 12 m bytes), plus the decoded length of every
// shuffled or delta frame that decodes to more than a quarter of it.
std::uint64_t streaming_spill_bound(const GraphReader& reader, std::uint64_t memory);

}  // namespace mosb
