// The one list of files every mosb place that publishes files writes (store, suites): JSON Lines,
// a header record then one record per file (spec/MANIFEST.md). The older suite MANIFEST (TSV,
// spec/GENERATORS.md) is still read and is replaced by this format on the next write.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mosb {

// Raw input `i` of the instance (FORMAT.md §7 `source.input.<i>.*`).
struct SourceInput {
  std::string name;
  std::uint64_t size = 0;
  std::string xxh3;  // 16 lowercase hex digits
  bool operator==(const SourceInput&) const = default;
};

// What a MANIFEST says of a solution file (spec/SOLUTIONS.md) it lists: the instance, objectives
// and query set its fronts answer, who made them and how their queries ended. Read from the file's
// bytes (describe_file), so two entries of equal SHA-256 say the same.
struct SolutionsEntry {
  std::string instance;  // the instance's content digest (`solution.instance_digest`)
  std::string epsilon;   // `solution.epsilon` as written; "0": the fronts claim to be exact
  std::string solver;    // `solution.solver.name`
  // The solvers whose fronts these are: a reference's agreeing solvers (its parameter `solvers`),
  // else the one solver.
  std::vector<std::string> solvers;
  std::map<std::string, std::uint64_t> statuses;  // query count per status name, those present
  std::uint64_t vectors = 0;                      // F: the vectors of every front together
  // The per-query statistics the file carries (runtime_seconds, expanded, ...), sorted by name.
  std::vector<std::string> statistics;
  bool operator==(const SolutionsEntry&) const = default;
};

struct ManifestEntry {
  std::string file;            // base name, no directory
  std::uint64_t size = 0;      // bytes of the file as stored (packed or not)
  std::string sha256;          // of the file bytes as stored, 64 hex digits
  std::string digest;          // FORMAT.md §8 content digest, 32 hex digits
  std::string format_version;  // "MAJOR.MINOR" of the file header
  bool packed = false;
  std::string benchmark;                // metadata `benchmark`; may be empty
  std::vector<std::string> views;       // names of the §7 views, sorted
  std::vector<std::string> query_sets;  // names of the queries sections, sorted
  std::vector<SourceInput> sources;     // in input order
  // Set for a solution file (file kind 2): then `views` holds its view (empty: bound to its
  // objectives alone), `query_sets` its query set, and `benchmark` its instance's, which a store
  // fills in from the instance's entry (the solution file does not carry it).
  std::optional<SolutionsEntry> solutions;
  bool operator==(const ManifestEntry&) const = default;
};

struct Manifest {
  std::vector<ManifestEntry> entries;  // sorted by file name, names unique
  // True when read from the older TSV MANIFEST: only file, size, digest and benchmark are known
  // (sha256 and the rest are empty).
  bool legacy = false;

  const ManifestEntry* find(std::string_view file) const;
};

inline constexpr std::string_view kManifestFormat = "mosb-manifest";
// Version 2 adds solution files (`kind`, spec/MANIFEST.md); a manifest that lists none is written
// as version 1, byte for byte what earlier mosb wrote, so that every reader still reads it.
inline constexpr int kManifestVersion = 2;
inline constexpr std::string_view kManifestName = "MANIFEST";

// Parses either format; throws mosb::Error "NAME:LINE: problem" on text that is neither.
Manifest parse_manifest(std::string_view text, const std::string& display_name);
// Reads and parses; throws mosb::Error (ErrorCode::io) naming the file when it cannot be read.
Manifest read_manifest(const std::filesystem::path& path);
// The JSON Lines text: header record, then the entries sorted by file name, keys sorted, no
// timestamps: equal manifests give equal bytes. Throws on a duplicate or invalid file name.
std::string serialize_manifest(const Manifest& manifest);
// serialize_manifest through mosb::AtomicFile: readers see the old or the new manifest.
void write_manifest(const std::filesystem::path& path, const Manifest& manifest);

// The entry for one mosb file, read from its bytes: opens it (header level), hashes it, and reads
// its metadata (a solution file: SolutionsEntry, its view and query set; `benchmark` left empty)
// (for a packed file whose metadata cannot be read without unpacking, the metadata-derived fields
// stay empty). `file` in the entry is the path's base name. `sha256`: the file's SHA-256 when the
// caller already has it (store pull computes it as the bytes arrive); otherwise it is computed from
// a read of the file, not its mapping, so that hashing a large file takes no memory of its size.
ManifestEntry describe_file(const std::filesystem::path& path,
                            std::optional<std::string> sha256 = std::nullopt);
class SolutionReader;
// describe_file of a solution file the caller has open: `reader` of the file at `path` (its
// decoded form when packed, which is not decoded again here).
ManifestEntry describe_solutions(const SolutionReader& reader, const std::filesystem::path& path,
                                 std::optional<std::string> sha256 = std::nullopt);

class Metadata;
// The §7 `source.input.<i>.*` records of an instance, in input order (i = 0, 1, ... until a name
// is absent); throws mosb::Error naming `display_name` on a size that is not a number.
std::vector<SourceInput> source_inputs(const Metadata& metadata, const std::string& display_name);

// True when `name` may be a manifest file name: non-empty, UTF-8, not "." or "..", no '/', not
// the manifest's own name, and no character a terminal would not show as itself: no control
// character (C0, DEL, C1: U+0080-U+009F), no line or paragraph separator, no bidirectional
// override, isolate or mark (U+202A-U+202E, U+2066-U+2069, ...), so that no name can pass for
// another when printed. The one name rule: MANIFESTs read and written, `store add`, raw inputs.
bool is_valid_manifest_file_name(std::string_view name);
// That rule in words, for the messages that refuse a name.
inline constexpr std::string_view kManifestFileNameRule =
    "a base name: UTF-8, no '/', no control, bidirectional or invisible formatting character, "
    "not '.', "
    "'..' or 'MANIFEST'";

}  // namespace mosb
