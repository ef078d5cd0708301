// A store: a directory of mosb files and the MANIFEST that lists them (spec/MANIFEST.md). Files are
// added atomically (each file, then the manifest, last); checking a store, or files against a
// published manifest, reports every kind of wrong entry; an instance is found by benchmark or view
// name. A store on a read-only directory can be listed, checked and opened without any write.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "mosb/graph_reader.hpp"
#include "mosb/manifest.hpp"
#include "mosb/pack.hpp"
#include "mosb/progress.hpp"

namespace mosb {

// One problem found with one file. `kind` is one of: missing, extra, wrong-size, wrong-sha256,
// wrong-digest, unreadable, damaged, unbound (a solution file whose instance is not listed).
struct FileProblem {
  std::string kind;
  std::string detail;  // one line, names the file
};

struct FileCheck {
  std::string file;  // base name (the listed name; for an extra file, its name)
  std::filesystem::path path;
  std::vector<FileProblem> problems;  // empty: the file is what the manifest says
  // Set when the file passes as the other form of the listed one (CheckOptions::accept_other_form).
  std::string note;
  bool ok() const { return problems.empty(); }
};

struct CheckOptions {
  unsigned threads = 0;  // 0: std::thread::hardware_concurrency()
  Progress progress;     // stage "verify": 0 first, then once per checked file, serialized
  // A file whose packedness differs from the listed entry's passes when its content digest is the
  // listed one and it verifies in full (a download unpacked with `mosb unpack`, or the reverse);
  // size and SHA-256 then describe the other form and are not compared. `verify --manifest`
  // accepts it; a store (Store::verify) must hold the listed bytes themselves.
  bool accept_other_form = false;
};

// Where the instances that solution files bind to are: content digest -> path.
using InstancePaths = std::map<std::string, std::filesystem::path>;
// The instance entries of a manifest, by content digest, in `directory`; a symlink is left out
// (a store follows none), so a solution file bound to it is reported unbound.
InstancePaths instance_paths(const Manifest& manifest, const std::filesystem::path& directory);

// Checks each (entry, path) pair: existence, size, SHA-256 (when listed), readability, its content
// digest, and that it is a mosb file passing verify --level full (a packed file is unpacked in
// memory first, so every frame is decoded and checked). A solution file's entry (`solutions`) is
// checked as `solutions verify --instance` checks it, against its instance in `instances`; one
// whose instance is not there is `unbound`. Results in input order.
std::vector<FileCheck> check_files(
    const std::vector<std::pair<ManifestEntry, std::filesystem::path>>& files,
    const CheckOptions& options, const InstancePaths& instances = {});

// The published manifest at `manifest_path` against files: with `paths` empty, every entry in the
// manifest's directory (a file missing there is reported); otherwise exactly those paths, each
// matched by base name (a path the manifest does not list is reported as `extra`).
std::vector<FileCheck> check_against_manifest(const std::filesystem::path& manifest_path,
                                              const std::vector<std::filesystem::path>& paths,
                                              const CheckOptions& options);

// One raw input of an instance (§7 `source.input.<i>.*`) compared with the file of that name in a
// directory. `problem` is empty when it matches.
struct SourceCheck {
  SourceInput expected;
  std::filesystem::path path;
  std::string problem;  // "", or one line: missing, wrong size, wrong XXH3
};
// Throws when the instance records no raw input (nothing to check).
std::vector<SourceCheck> check_sources(const GraphReader& instance,
                                       const std::filesystem::path& directory);

// XXH3-64 of a file's bytes as 16 lowercase hex digits, streamed (as `source.input.<i>.xxh3`).
std::string xxh3_file(const std::filesystem::path& path);

// A store's own directories (names starting with '.', which store verification skips).
inline constexpr std::string_view kCacheDirectory = ".cache";  // unpacked copies of packed entries
// Packed by add, not yet placed: one directory `PID-XXXXXX` per add, removed when it ends; one
// left by an add that was interrupted or killed is removed by the next add once that PID has ended
// (the rule of AtomicFile's stale temporaries).
inline constexpr std::string_view kStagingDirectory = ".staging";

// A released store's description for people and its summary for programs (`suite release`).
inline constexpr std::string_view kStoreReadme = "README.md";
inline constexpr std::string_view kStoreSummary = "SUMMARY.csv";

// True for the names a store keeps for itself, which no entry may have: MANIFEST, README.md and
// SUMMARY.csv, and every name starting with '.' (the MANIFEST's and the entries' temporaries
// `.NAME.tmp-PID-XXXXXX`, .cache, .staging, the writers' lock .lock, and whatever a later version
// adds).
bool is_reserved_store_name(std::string_view name);

// A store's entry resolved for a benchmark: the reader, the file and the view to use.
struct StoreInstance {
  GraphReader reader;  // opened at VerifyLevel::full
  ManifestEntry entry;
  // The file mapped: the entry itself; for a packed entry its unpacked copy in the store's cache,
  // or, when the cache cannot be written (a read-only store), the packed file (then unpacked into
  // memory owned by `reader`).
  std::filesystem::path path;
  std::optional<View> view;  // nullopt: the whole file (every objective)
  std::string query_set;     // the view's query set, or "" when it names none
};

class Store {
 public:
  // Creates `directory` (if needed) and an empty manifest; refuses a directory that has one.
  static Store init(const std::filesystem::path& directory);
  // Reads the manifest; throws mosb::Error when `directory` has none, or when it lists a reserved
  // name (is_reserved_store_name). Writes nothing.
  static Store open(const std::filesystem::path& directory);

  const std::filesystem::path& directory() const { return directory_; }
  const Manifest& manifest() const { return manifest_; }
  std::filesystem::path manifest_path() const { return directory_ / kManifestName; }

  struct AddOptions {
    bool move = false;  // rename (or copy, then remove) the source instead of copying it
    // Pack each unpacked file on the way in (a packed one is stored as it is). The packed form is
    // written to DIR/.staging first, so a name conflict is found before anything is replaced.
    std::optional<PackOptions> pack;
    Progress progress;  // stage "pack" (when packing) and stage "add": once per file
    // Empty, or one entry per file, in order: each file must then be exactly that entry (size,
    // SHA-256 and content digest, as a published MANIFEST lists it; `store pull`), else the add
    // is refused before anything is placed. Compared before packing.
    std::vector<ManifestEntry> expect;
    // Empty, or one SHA-256 per file, in order, that the caller computed over the very bytes it
    // wrote (store pull, as they arrived): not computed again, and a file the store then renames
    // into place is not hashed again once placed.
    std::vector<std::string> sha256;
    // The working memory of each file's check (verify_file_streaming), whatever the file's size.
    std::uint64_t check_memory = StreamingVerifyOptions{}.memory;
    // The most disk each check's spill file may take (StreamingVerifyOptions::disk); nullopt:
    // default_check_disk(the file's size, check_memory). A file whose check would need more is
    // refused before the check spills.
    std::optional<std::uint64_t> check_disk;
    // The buffers of those checks: the caller's, kept from one add to the next (store pull, one
    // per transfer thread), or none (each check maps its own).
    VerifyWorkspace* check_workspace = nullptr;
  };
  // Solution files (file kind 2) are taken too, after the instances of the same add: each is
  // checked as verify_solutions checks it against its instance, which the store lists or the
  // same add brings (else refused), gets its instance's benchmark, and is packed with `pack` like
  // an instance (format 1.6, spec/SOLUTIONS.md §1); a second exact file (ε = 0) of one instance,
  // view and query set is refused. With `expect`, a solution file's described entry must equal the
  // expected one.
  // Copies (or moves, or packs) each file in under its base name, each through mosb::AtomicFile,
  // then rewrites the manifest atomically, last. Refused before anything is written: a reserved
  // or invalid base name, two files of one name, a file that does not open as a mosb file or fails
  // verify --level full (a packed one decoded; checked by verify_file_streaming, in
  // `check_memory`, its spill file in DIR/.staging), a name already listed with other bytes (the
  // same bytes again are accepted: a retry after an interrupted add). Files are checked (and
  // packed) first; then, holding the store's StoreLock, the manifest is read again, each file
  // placed and the manifest rewritten, so concurrent adds each see the others' entries. A symlink
  // at DIR/.staging, DIR/.lock or where an entry goes is refused, never followed. With `move`, a
  // source is removed only after the manifest listing its copy is in place. Returns the new
  // entries.
  std::vector<ManifestEntry> add(const std::vector<std::filesystem::path>& files,
                                 const AddOptions& options);

  // Removes the entries of these base names (as the MANIFEST lists them), their files, and the
  // unpacked copy DIR/.cache/FILE of a packed one. Refused before anything changes (mosb::Error
  // naming the file): a name the manifest does not list, and an instance whose references stay
  // listed (solution files bound to its content digest, which no other listed instance has), named
  // in the message: remove them with it, or first. Holding the store's StoreLock, the manifest is
  // rewritten first, then the files removed: a crash in between leaves files the manifest no
  // longer lists, which verify() reports as `extra`. Returns the removed entries.
  std::vector<ManifestEntry> remove(const std::vector<std::string>& files);

  // Every entry (see check_files) plus every file in the directory the manifest does not list
  // (`extra`; reserved names, the store's own files, are not counted). An entry that is a symlink
  // is `unreadable` and not followed.
  std::vector<FileCheck> verify(const CheckOptions& options) const;

  // Resolves `name`, in this order: "BENCHMARK/VIEW"; a view name served by exactly one entry;
  // a benchmark name served by exactly one entry (with its only view if it has exactly one,
  // otherwise the whole file). Throws mosb::Error (ErrorCode::not_found) listing what was
  // ambiguous or what exists. A packed entry is unpacked into DIR/.cache/FILE on first use
  // (atomically; the copy is verified in full and against the manifest's digest at every use, and
  // made again when it does not match). A symlink at the entry, DIR/.cache or DIR/.cache/FILE is
  // refused (mosb::Error naming it), never followed; a .cache this call made and could not fill is
  // removed again.
  StoreInstance instance(std::string_view name) const;

  // The reference (the exact solution file, ε = 0) the store lists for each instance given by
  // content digest, for every view and query set it has one of, each checked against its entry
  // before it is returned (a regular file, not a symlink, of the listed size and SHA-256: bytes
  // that are not the listed ones are never read as a reference; mosb::Error naming the file and
  // `mosb store verify` otherwise). `missing`: the digests the store has no reference for.
  struct References {
    std::vector<std::filesystem::path> files;  // in manifest order
    std::vector<std::string> missing;          // sorted
  };
  References references(const std::set<std::string>& instance_digests) const;

  // The unpacked copy DIR/.cache/FILE of the packed entry `file`, made as instance() makes it
  // (verified in full against the entry's digest, made again when it does not match), so the
  // first instance() maps it at once. Throws mosb::Error when `file` is not a listed packed entry
  // or the copy cannot be written (a read-only store).
  std::filesystem::path unpack(std::string_view file) const;

 private:
  Store(std::filesystem::path directory, Manifest manifest)
      : directory_(std::move(directory)), manifest_(std::move(manifest)) {}
  std::filesystem::path directory_;
  Manifest manifest_;
};

}  // namespace mosb
