#include "mosb/store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <iterator>
#include <mutex>
#include <optional>
#include <set>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/parallel.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/internal/xxh3.hpp"
#include "mosb/pack.hpp"
#include "mosb/sha256.hpp"
#include "mosb/solution_file.hpp"
#include "mosb/solution_verify.hpp"
#include "mosb/store_lock.hpp"
#include "mosb/verify.hpp"

namespace mosb {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kChunk = std::size_t{1} << 20;

// A file descriptor that closes itself.
struct InputFd {
  explicit InputFd(const fs::path& path)
      : fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)) {
    if (fd < 0)
      throw Error(ErrorCode::io, path.string() + ": cannot open: " + std::strerror(errno));
  }
  ~InputFd() { ::close(fd); }
  InputFd(const InputFd&) = delete;
  InputFd& operator=(const InputFd&) = delete;
  // Calls `consume(data, size)` for each chunk of the file.
  template <class F>
  void read_all(const fs::path& path, F consume) const {
    std::vector<char> buffer(kChunk);
    read_chunks(fd, path, buffer, consume);
  }
  int fd;
};

// The instance a solution file's fronts belong to, opened for verify_solutions: mapped, or
// decoded into memory when packed.
GraphReader open_instance(const fs::path& path) {
  return mosb::load(path, VerifyLevel::full);
}

// The first problem of a solution file as a store takes it: its payload, then its fronts against
// the instance it binds to (verify_solutions: the binding, dominance, paths), or nullopt.
std::optional<std::string> solutions_problem(const SolutionReader& solutions,
                                             const fs::path& instance) {
  if (auto found = solutions.verify_payload()) return found;
  return verify_solutions(solutions, open_instance(instance));
}

// The checks of a listed instance file past its size and SHA-256.
void check_instance(FileCheck& c, const ManifestEntry& e, const fs::path& path,
                    bool accept_other_form) {
  auto problem = [&](std::string kind, std::string detail) {
    c.problems.push_back({std::move(kind), path.string() + ": " + std::move(detail)});
  };
  const auto reader = GraphReader::open(path);
  const auto digest = reader.digest();
  if (digest != e.digest)
    problem("wrong-digest", "content digest " + digest + ", the manifest says " + e.digest);
  // A packed file is checked as it will be used: unpacked (every frame decoded and checked
  // against its section checksum), then verified in full.
  const bool packed = is_packed(reader.header());
  const auto checked = packed ? mosb::load(path) : reader;
  if (const auto found = verify(checked, VerifyLevel::full)) {
    problem("damaged", *found);
  } else if (accept_other_form && digest == e.digest && packed != e.packed) {
    // `mosb unpack` (or `pack`) of the listed file: other bytes, the same content, which the
    // digest proves and the full verification has just checked.
    std::erase_if(c.problems, [](const FileProblem& p) {
      return p.kind == "wrong-size" || p.kind == "wrong-sha256";
    });
    c.note = packed ? "packed form of the listed unpacked file"
                    : "unpacked form of the listed packed file";
  }
}

// The checks of a listed solution file past its size and SHA-256: a solution file of the listed
// content, bound to an instance the manifest lists (`unbound` otherwise), whose fronts that
// instance verifies.
void check_solutions(FileCheck& c, const ManifestEntry& e, const fs::path& path,
                     const InstancePaths& instances) {
  auto problem = [&](std::string kind, std::string detail) {
    c.problems.push_back({std::move(kind), path.string() + ": " + std::move(detail)});
  };
  const auto reader = SolutionReader::open(path);
  if (const auto digest = reader.digest(); digest != e.digest)
    problem("wrong-digest", "content digest " + digest + ", the manifest says " + e.digest);
  const auto instance = instances.find(reader.instance_digest());
  if (instance == instances.end()) {
    if (auto found = reader.verify_payload()) problem("damaged", *found);
    problem("unbound", "solutions of instance " + reader.instance_digest() +
                           ", which the manifest does not list");
  } else if (auto found = solutions_problem(reader, instance->second)) {
    problem("damaged", *found);
  }
}

FileCheck check_one(const ManifestEntry& e, const fs::path& path, bool accept_other_form,
                    const InstancePaths& instances) {
  FileCheck c{e.file, path, {}, {}};
  auto problem = [&](std::string kind, std::string detail) {
    c.problems.push_back({std::move(kind), path.string() + ": " + std::move(detail)});
  };
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (!fs::exists(status)) {
    problem("missing", "listed in the manifest but absent");
    return c;
  }
  if (!fs::is_regular_file(status)) {
    problem("unreadable", "not a regular file");
    return c;
  }
  const auto size = fs::file_size(path, ec);
  if (!ec && size != e.size)
    problem("wrong-size",
            std::to_string(size) + " bytes, the manifest says " + std::to_string(e.size));
  std::string sha;
  try {
    sha = sha256_file(path);
  } catch (const Error& error) {
    c.problems.push_back({"unreadable", error.what()});
    return c;
  }
  if (!e.sha256.empty() && sha != e.sha256)
    problem("wrong-sha256", "SHA-256 " + sha + ", the manifest says " + e.sha256);
  try {
    if (e.solutions)
      check_solutions(c, e, path, instances);
    else
      check_instance(c, e, path, accept_other_form);
  } catch (const Error& error) {
    // Out of memory (or past the memory available) is this machine's limit, not damage.
    const bool unreadable = error.code() == ErrorCode::io || error.code() == ErrorCode::no_memory;
    c.problems.push_back({unreadable ? "unreadable" : "damaged", error.what()});
  }
  return c;
}

void copy_into(const fs::path& source, AtomicFile& out) {
  InputFd in(source);
  in.read_all(source, [&](const char* data, std::size_t size) { out.write(data, size); });
}

// Throws when `path` itself is a symlink. The store makes none, so one there was planted, and
// following it would read, write or delete outside the store.
void refuse_symlink(const fs::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0 && S_ISLNK(st.st_mode))
    throw Error(path.string() + ": is a symbolic link, which the store did not make; not followed");
}

// One of the store's own directories (.cache, .staging): made when absent, refused when something
// else sits there. True when this call made it.
bool own_directory(const fs::path& path) {
  if (::mkdir(path.c_str(), 0777) == 0) return true;
  const int error = errno;
  struct stat st {};
  if (error != EEXIST || ::lstat(path.c_str(), &st) != 0)
    throw Error(ErrorCode::io, path.string() + ": cannot create: " + std::strerror(error));
  refuse_symlink(path);
  if (!S_ISDIR(st.st_mode))
    throw Error(path.string() + ": is not a directory; the store keeps its own files there");
  return false;
}

// The PID in a staging directory's name `PID-XXXXXX` (mkdtemp), or 0.
long staging_pid(const std::string& name) {
  const auto dash = name.find('-');
  if (dash == 0 || dash > 10 || dash == std::string::npos || name.size() != dash + 7) return 0;
  long pid = 0;
  for (std::size_t i = 0; i < dash; ++i) {
    if (name[i] < '0' || name[i] > '9') return 0;
    pid = pid * 10 + (name[i] - '0');
  }
  return pid;
}

// Removes the staging directories of adds whose process has ended (interrupted, killed), then
// .staging itself when empty. Nothing else is touched: what the store cannot name is not its own.
void sweep_staging(const fs::path& staging) {
  struct stat st {};
  if (::lstat(staging.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return;  // absent, or refused
  std::error_code ec;
  for (fs::directory_iterator it(staging, ec), end; !ec && it != end; it.increment(ec)) {
    const long pid = staging_pid(it->path().filename().string());
    std::error_code ignored;
    // remove_all removes a symlink, never what it leads to.
    if (pid != 0 && process_has_ended(pid)) fs::remove_all(it->path(), ignored);
  }
  ::rmdir(staging.c_str());  // fails, harmlessly, while it holds anything
}

// Removes DIR/.cache when it is empty and unchanged for a minute (earlier versions left it empty
// after a refused entry). The minute spares a `store instance` that has just made it and is about
// to unpack into it; rmdir removes neither a symlink nor a directory that holds anything.
void sweep_empty_cache(const fs::path& cache) {
  struct stat st {};
  if (::lstat(cache.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return;
  if (std::time(nullptr) - st.st_mtime >= 60) ::rmdir(cache.c_str());
}

// This add's own directory in DIR/.staging: unique per process and call, so concurrent adds
// never write one another's files. Removed, with what it holds, on destruction.
class Staging {
 public:
  explicit Staging(const fs::path& store) : parent_(store / kStagingDirectory) {}
  ~Staging() {
    if (path_.empty()) return;
    std::error_code ec;
    fs::remove_all(path_, ec);
    ::rmdir(parent_.c_str());  // fails, harmlessly, while a concurrent add still uses it
  }
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;

  // Where a check's spill file goes (an unnamed O_TMPFILE: nothing to clean up): DIR/.staging
  // when it exists, else the store itself; the same file system as the entries.
  fs::path scratch_directory() const {
    std::error_code ec;
    return fs::is_directory(parent_, ec) ? parent_ : parent_.parent_path();
  }

  fs::path file(const std::string& name) {
    // A concurrent add's sweep may remove an empty .staging between its creation and mkdtemp.
    for (int attempt = 0; path_.empty(); ++attempt) {
      own_directory(parent_);
      std::string name_template = (parent_ / (std::to_string(::getpid()) + "-XXXXXX")).string();
      if (::mkdtemp(name_template.data()) != nullptr) {
        path_ = name_template;
      } else if (const int error = errno; error != ENOENT || attempt == 3) {
        throw Error(ErrorCode::io, parent_.string() + ": cannot create: " + std::strerror(error));
      }
    }
    return path_ / name;
  }

 private:
  fs::path parent_;
  fs::path path_;  // empty until the first file
};

// The unpacked copy at `copy` when it holds the entry's content, verified in full.
std::optional<GraphReader> open_cached(const fs::path& copy, const ManifestEntry& e) {
  std::error_code ec;
  if (!fs::exists(copy, ec)) return std::nullopt;
  try {
    auto reader = GraphReader::open(copy, VerifyLevel::full);
    if (reader.digest() == e.digest) return reader;
  } catch (const Error&) {
    // Made again by the caller from the packed file, which is checked as it is unpacked.
  }
  return std::nullopt;
}

// The reader of a packed entry: its unpacked copy in DIR/.cache, made first when absent or not
// the entry's content (a damaged or an earlier version's copy), or, when the store cannot be
// written, the packed file unpacked into memory.
std::pair<GraphReader, fs::path> open_packed(const fs::path& directory, const ManifestEntry& e) {
  const auto packed = directory / e.file;
  const auto cache = directory / kCacheDirectory;
  const auto copy = cache / e.file;
  refuse_symlink(cache);
  refuse_symlink(copy);
  if (auto reader = open_cached(copy, e)) return {std::move(*reader), copy};
  // A read-only store, or a directory where the copy belongs (rename cannot replace it, and the
  // store does not delete what it did not make): decoded into memory, nothing written.
  std::error_code ec;
  if (::access((fs::is_directory(cache, ec) ? cache : directory).c_str(), W_OK) != 0 ||
      fs::is_directory(copy, ec))
    return {mosb::load(packed, VerifyLevel::full), packed};
  const bool made = own_directory(cache);
  try {
    unpack_file(packed, copy);
  } catch (...) {
    if (made) ::rmdir(cache.c_str());  // no empty .cache left by a refused entry
    throw;
  }
  return {GraphReader::open(copy, VerifyLevel::full), copy};
}

}  // namespace

InstancePaths instance_paths(const Manifest& manifest, const fs::path& directory) {
  InstancePaths out;
  for (const auto& e : manifest.entries) {
    std::error_code ec;
    if (!e.solutions && !fs::is_symlink(fs::symlink_status(directory / e.file, ec)))
      out.emplace(e.digest, directory / e.file);
  }
  return out;
}

std::vector<FileCheck> check_files(const std::vector<std::pair<ManifestEntry, fs::path>>& files,
                                   const CheckOptions& options, const InstancePaths& instances) {
  std::vector<FileCheck> checks(files.size());
  std::mutex progress_mutex;
  std::size_t done = 0;
  report(options.progress, "verify", 0, files.size());
  parallel_for(files.size(), thread_count(options.threads), [&](std::size_t i) {
    try {
      checks[i] = check_one(files[i].first, files[i].second, options.accept_other_form, instances);
    } catch (const std::exception& error) {  // bad_alloc, filesystem_error: a report, not a crash
      checks[i] = {files[i].first.file, files[i].second, {{"unreadable", error.what()}}, {}};
    }
    std::lock_guard lock(progress_mutex);
    report(options.progress, "verify", ++done, files.size());
  });
  return checks;
}

std::vector<FileCheck> check_against_manifest(const fs::path& manifest_path,
                                              const std::vector<fs::path>& paths,
                                              const CheckOptions& options) {
  const auto manifest = read_manifest(manifest_path);
  const auto directory = manifest_path.parent_path();
  std::vector<std::pair<ManifestEntry, fs::path>> files;
  std::vector<FileCheck> unlisted;
  if (paths.empty()) {
    for (const auto& e : manifest.entries) files.emplace_back(e, directory / e.file);
  } else {
    for (const auto& path : paths) {
      const auto name = path.filename().string();
      if (const auto* e = manifest.find(name))
        files.emplace_back(*e, path);
      else
        unlisted.push_back(
            {name,
             path,
             {{"extra", path.string() + ": not listed in " + manifest_path.string()}},
             {}});
    }
  }
  auto checks = check_files(files, options, instance_paths(manifest, directory));
  checks.insert(checks.end(), unlisted.begin(), unlisted.end());
  return checks;
}

std::string xxh3_file(const fs::path& path) {
  InputFd in(path);
  Xxh3Stream hash;
  in.read_all(path, [&](const char* data, std::size_t size) { hash.update(data, size); });
  return hex64(hash.digest());
}

std::vector<SourceCheck> check_sources(const GraphReader& instance, const fs::path& directory) {
  const auto inputs = source_inputs(instance.metadata(), instance.display_name());
  if (inputs.empty())
    throw Error(instance.display_name() + ": records no raw input (no source.input.* metadata)");
  std::vector<SourceCheck> checks;
  for (const auto& input : inputs) {
    SourceCheck c{input, directory / input.name, {}};
    const auto where = c.path.string() + ": ";
    std::error_code ec;
    if (!is_valid_manifest_file_name(input.name)) {
      c.problem = instance.display_name() + ": raw input name '" + input.name + "' is not " +
                  std::string(kManifestFileNameRule);
    } else if (!fs::exists(c.path, ec)) {
      c.problem = where + "missing";
    } else {
      try {
        const auto size = fs::file_size(c.path);
        const auto hash = xxh3_file(c.path);
        if (size != input.size)
          c.problem = where + std::to_string(size) + " bytes, the instance was built from " +
                      std::to_string(input.size);
        else if (hash != input.xxh3)
          c.problem = where + "XXH3 " + hash + ", the instance was built from " + input.xxh3;
      } catch (const std::exception& error) {
        c.problem = error.what();
      }
    }
    checks.push_back(std::move(c));
  }
  return checks;
}

bool is_reserved_store_name(std::string_view name) {
  return name == kManifestName || name == kStoreReadme || name == kStoreSummary ||
         name.starts_with('.');
}

namespace {

// The manifest of a store: a listed reserved name would make the store hand out, check or
// replace one of its own files as an entry.
Manifest read_store_manifest(const fs::path& path) {
  auto manifest = read_manifest(path);
  for (const auto& e : manifest.entries)
    if (is_reserved_store_name(e.file))
      throw Error(path.string() + ": lists '" + e.file +
                  "', a name the store keeps for itself (MANIFEST, README.md, SUMMARY.csv, "
                  "names starting with '.')");
  return manifest;
}

// Every base name may become an entry: checked before any file is read or anything written.
void check_names(const std::vector<fs::path>& files) {
  std::set<std::string> names;
  for (const auto& source : files) {
    const auto name = source.filename().string();
    if (is_reserved_store_name(name))
      throw Error(source.string() + ": cannot be added as '" + name +
                  "': the store keeps MANIFEST, README.md, SUMMARY.csv and names starting with "
                  "'.' for itself");
    if (!is_valid_manifest_file_name(name))
      throw Error(source.string() + ": '" + name + "' cannot be an entry's name (" +
                  std::string(kManifestFileNameRule) + ")");
    if (!names.insert(name).second)
      throw Error(source.string() + ": a second file named '" + name + "' in one add");
  }
}

// One file of an add: its entry, and where the stored bytes come from.
struct Placement {
  ManifestEntry entry;
  fs::path source;  // as given
  fs::path from;    // the source, or its packed form in the staging directory
  bool staged = false;
  bool hashed = false;  // entry.sha256 was computed by the caller as it wrote `from`
};

// Throws when the file described as `found` is not the entry `expected`, naming what differs.
void check_expected(const fs::path& source, const ManifestEntry& found,
                    const ManifestEntry& expected) {
  std::string differs;
  if (found.size != expected.size)
    differs =
        std::to_string(found.size) + " bytes, the manifest says " + std::to_string(expected.size);
  else if (found.sha256 != expected.sha256)
    differs = "SHA-256 " + found.sha256 + ", the manifest says " + expected.sha256;
  else if (found.digest != expected.digest)
    differs = "content digest " + found.digest + ", the manifest says " + expected.digest;
  else if (found.solutions.has_value() != expected.solutions.has_value())
    differs = found.solutions ? "a solution file, which the manifest lists as an instance"
                              : "an instance, which the manifest lists as a solution file";
  else if (found.solutions &&
           (*found.solutions != *expected.solutions || found.views != expected.views ||
            found.query_sets != expected.query_sets))
    differs =
        "the manifest describes other fronts (instance, view, query set, epsilon, solvers or "
        "statuses) than the file holds";
  if (!differs.empty()) throw Error(ErrorCode::damaged, source.string() + ": " + differs);
}

// With --pack, an unpacked file of an add is placed from its packed form in the staging directory.
void stage_packed(Placement& p, const Store::AddOptions& options, Staging& staging) {
  if (!options.pack || p.entry.packed) return;
  p.from = staging.file(p.entry.file);
  pack_file(p.source, p.from, *options.pack);
  p.staged = true;
  p.hashed = false;
  p.entry = describe_file(p.from);
}

Placement prepare(const fs::path& source, const Store::AddOptions& options,
                  const ManifestEntry* expected, const std::string* sha256, Staging& staging) {
  Placement p{describe_file(source, sha256 ? std::optional(*sha256) : std::nullopt), source, source,
              false, sha256 != nullptr};
  if (expected != nullptr) check_expected(source, p.entry, *expected);
  // Packed or not, in working memory that does not grow with the file.
  const auto found =
      verify_file_streaming(source, {options.check_memory, staging.scratch_directory(),
                                     options.check_workspace, options.check_disk});
  if (found.problem)
    throw Error(ErrorCode::damaged, source.string() + ": file is damaged: " + *found.problem);
  stage_packed(p, options, staging);
  return p;
}

// A solution file of an add: checked against its instance, which is listed in the store or added
// by the same add (`added`), given that instance's benchmark, and packed with --pack like an
// instance.
Placement prepare_solutions(const fs::path& source, const Store::AddOptions& options,
                            const ManifestEntry* expected, const std::string* sha256,
                            Staging& staging, const fs::path& directory, const Manifest& manifest,
                            const std::vector<Placement>& added) {
  const auto solutions = SolutionReader::open(source);
  Placement p{describe_solutions(solutions, source, sha256 ? std::optional(*sha256) : std::nullopt),
              source, source, false, sha256 != nullptr};
  if (expected != nullptr) check_expected(source, p.entry, *expected);
  const auto& digest = p.entry.solutions->instance;
  const ManifestEntry* instance = nullptr;
  fs::path instance_path;
  for (const auto& a : added)
    if (!a.entry.solutions && a.entry.digest == digest) instance = &a.entry, instance_path = a.from;
  if (instance == nullptr)
    for (const auto& e : manifest.entries)
      if (!e.solutions && e.digest == digest) instance = &e, instance_path = directory / e.file;
  if (instance == nullptr)
    throw Error(ErrorCode::not_found,
                source.string() + ": solutions of instance " + digest +
                    ", which the store does not list (add the instance first, or with it)");
  refuse_symlink(instance_path);
  if (const auto problem = solutions_problem(solutions, instance_path))
    throw Error(ErrorCode::damaged, source.string() + ": " + *problem);
  stage_packed(p, options, staging);
  p.entry.benchmark = instance->benchmark;
  return p;
}

// Whose fronts a store keeps once: the exact ones (ε = 0) of one instance, view and query set, so
// that "the reference of this instance" has one answer.
bool same_exact_fronts(const ManifestEntry& a, const ManifestEntry& b) {
  return a.solutions && b.solutions && a.file != b.file && a.solutions->epsilon == "0" &&
         b.solutions->epsilon == "0" && a.solutions->instance == b.solutions->instance &&
         a.views == b.views && a.query_sets == b.query_sets;
}

void check_conflicts(const Manifest& manifest, const std::vector<Placement>& placements) {
  for (const auto& p : placements) {
    if (const auto* listed = manifest.find(p.entry.file);
        listed && (listed->sha256.empty() || listed->sha256 != p.entry.sha256))
      throw Error(p.source.string() + ": the store already lists a different '" + p.entry.file +
                  "'");
    auto exact_twice = [&](const ManifestEntry& other) {
      if (same_exact_fronts(p.entry, other))
        throw Error(p.source.string() + ": exact fronts of instance " +
                    p.entry.solutions->instance +
                    (p.entry.views.empty() ? "" : ", view " + p.entry.views.front()) +
                    ", query set " + p.entry.query_sets.front() + ", which '" + other.file +
                    "' already holds (a store keeps one reference per binding)");
    };
    for (const auto& e : manifest.entries) exact_twice(e);
    for (const auto& other : placements) exact_twice(other.entry);
  }
}

// True when the file was renamed into place (the bytes checked are the bytes placed).
bool place(const fs::path& directory, const Placement& p, bool move) {
  const auto target = directory / p.entry.file;
  refuse_symlink(target);
  std::error_code ec;
  // A file already in place is adopted where it lies; a rename within one file system is atomic
  // by itself (a symlinked source is copied: moving the link would make the entry a link);
  // anything else is copied through a temporary, and a --move source stays until the manifest
  // lists its copy.
  if (!p.staged && fs::exists(target, ec) && fs::equivalent(target, p.source, ec)) return false;
  if (p.staged || (move && !fs::is_symlink(fs::symlink_status(p.from, ec)))) {
    fs::rename(p.from, target, ec);
    if (!ec) return true;
  }
  AtomicFile out(target);
  copy_into(p.from, out);
  out.commit();
  return false;
}

// Places every file, checks the placed bytes, then replaces the manifest. The caller holds the
// store's lock and `manifest` is what the MANIFEST listed once it was taken.
Manifest place_all(const fs::path& directory, const Manifest& manifest,
                   const std::vector<Placement>& placements, const Store::AddOptions& options) {
  report(options.progress, "add", 0, placements.size());
  std::vector<bool> renamed(placements.size());
  for (std::size_t i = 0; i < placements.size(); ++i) {
    renamed[i] = place(directory, placements[i], options.move);
    report(options.progress, "add", i + 1, placements.size());
  }
  // The bytes just placed are the bytes described: a source changed between the check and the
  // copy is caught here, before the manifest names it. A file the caller hashed as it wrote it and
  // the store renamed (store pull's own staging) is the inode checked, and needs no second pass.
  for (std::size_t i = 0; i < placements.size(); ++i) {
    const auto& p = placements[i];
    if (p.hashed && renamed[i]) continue;
    if (sha256_file(directory / p.entry.file) != p.entry.sha256)
      throw Error(p.source.string() + ": changed while it was being added");
  }
  Manifest next = manifest;
  next.legacy = false;
  for (const auto& p : placements) {
    auto it = std::find_if(next.entries.begin(), next.entries.end(),
                           [&](const ManifestEntry& x) { return x.file == p.entry.file; });
    if (it != next.entries.end())
      *it = p.entry;
    else
      next.entries.push_back(p.entry);
  }
  std::sort(next.entries.begin(), next.entries.end(),
            [](const auto& a, const auto& b) { return a.file < b.file; });
  write_manifest(directory / kManifestName, next);
  return next;
}

}  // namespace

Store Store::init(const fs::path& directory) {
  std::error_code ec;
  fs::create_directories(directory, ec);
  if (ec) throw Error(ErrorCode::io, directory.string() + ": cannot create: " + ec.message());
  const auto path = directory / kManifestName;
  if (fs::exists(path, ec))
    throw Error(path.string() + ": already exists; this directory is a store (or a suite)");
  write_manifest(path, {});
  return {directory, {}};
}

Store Store::open(const fs::path& directory) {
  const auto path = directory / kManifestName;
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw Error(
        ErrorCode::not_found,
        directory.string() + ": not a store (no MANIFEST; create one with mosb store init)");
  return {directory, read_store_manifest(path)};
}

std::vector<ManifestEntry> Store::add(const std::vector<fs::path>& files,
                                      const AddOptions& options) {
  // Everything is checked (and packed) before anything the manifest lists is written.
  check_names(files);
  if (!options.expect.empty() && options.expect.size() != files.size())
    throw Error(ErrorCode::invalid_argument, "Store::add: one expected entry per file, or none");
  if (!options.sha256.empty() && options.sha256.size() != files.size())
    throw Error(ErrorCode::invalid_argument, "Store::add: one SHA-256 per file, or none");
  sweep_staging(directory_ / kStagingDirectory);
  sweep_empty_cache(directory_ / kCacheDirectory);
  Staging staging(directory_);  // removed, with anything not placed, on every way out
  // Instances first: a solution file is checked against its instance, which may come with it.
  std::vector<std::size_t> solution_files;
  std::vector<Placement> placements;
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (options.pack) report(options.progress, "pack", i, files.size());
    const auto* expected = options.expect.empty() ? nullptr : &options.expect[i];
    const auto* sha256 = options.sha256.empty() ? nullptr : &options.sha256[i];
    if (stated_file_kind(map_file(files[i]).bytes) == format::FileKind::solutions)
      solution_files.push_back(i);
    else
      placements.push_back(prepare(files[i], options, expected, sha256, staging));
  }
  for (const auto i : solution_files) {
    if (options.pack) report(options.progress, "pack", i, files.size());
    placements.push_back(prepare_solutions(files[i], options,
                                           options.expect.empty() ? nullptr : &options.expect[i],
                                           options.sha256.empty() ? nullptr : &options.sha256[i],
                                           staging, directory_, manifest_, placements));
  }
  if (options.pack) report(options.progress, "pack", files.size(), files.size());
  check_conflicts(manifest_, placements);  // refused at once, without waiting for the lock
  {
    const StoreLock lock(directory_);
    // Concurrent adds may have listed files since this store was opened.
    auto current = read_store_manifest(manifest_path());
    check_conflicts(current, placements);
    manifest_ = place_all(directory_, current, placements, options);
  }
  if (options.move)
    for (const auto& source : files) {
      std::error_code ec;
      if (fs::exists(source, ec) && !fs::equivalent(source, directory_ / source.filename(), ec))
        fs::remove(source, ec);
    }
  std::vector<ManifestEntry> added;
  added.reserve(placements.size());
  for (auto& p : placements) added.push_back(std::move(p.entry));
  return added;
}

std::vector<ManifestEntry> Store::remove(const std::vector<std::string>& files) {
  const StoreLock lock(directory_);
  Manifest next = read_store_manifest(manifest_path());
  const std::set<std::string> names(files.begin(), files.end());
  for (const auto& name : files)
    if (next.find(name) == nullptr)
      throw Error(ErrorCode::not_found,
                  (directory_ / name).string() + ": not listed in the store's MANIFEST");
  auto kept = [&](const ManifestEntry& e) { return !names.contains(e.file); };
  for (const auto& e : next.entries) {
    if (kept(e) || e.solutions) continue;
    const bool another_copy = std::any_of(next.entries.begin(), next.entries.end(), [&](auto& x) {
      return kept(x) && !x.solutions && x.digest == e.digest;
    });
    std::string bound;
    for (const auto& x : next.entries)
      if (kept(x) && x.solutions && x.solutions->instance == e.digest)
        bound += (bound.empty() ? "" : ", ") + x.file;
    if (!bound.empty() && !another_copy)
      throw Error(ErrorCode::invalid_argument, (directory_ / e.file).string() +
                                                   ": its references stay in the store (" + bound +
                                                   "); remove them with it, or first");
  }
  std::vector<ManifestEntry> removed;
  for (const auto& e : next.entries)
    if (!kept(e)) removed.push_back(e);
  std::erase_if(next.entries, [&](const ManifestEntry& e) { return !kept(e); });
  next.legacy = false;
  write_manifest(manifest_path(), next);
  manifest_ = next;
  const auto cache = directory_ / kCacheDirectory;
  std::error_code ec;
  const bool cache_is_ours = !fs::is_symlink(fs::symlink_status(cache, ec));
  for (const auto& e : removed) {
    fs::remove(directory_ / e.file, ec);  // a symlink itself, never what it points to
    if (ec) throw Error(ErrorCode::io, (directory_ / e.file).string() + ": " + ec.message());
    if (e.packed && cache_is_ours) fs::remove(cache / e.file, ec);
  }
  return removed;
}

std::vector<FileCheck> Store::verify(const CheckOptions& options) const {
  std::vector<std::pair<ManifestEntry, fs::path>> files;
  std::vector<FileCheck> links;
  for (const auto& e : manifest_.entries) {
    const auto path = directory_ / e.file;
    std::error_code absent;
    if (fs::is_symlink(fs::symlink_status(path, absent)))
      links.push_back({e.file,
                       path,
                       {{"unreadable", path.string() + ": is a symbolic link, "
                                                       "which the store did not "
                                                       "make; not followed"}},
                       {}});
    else
      files.emplace_back(e, path);
  }
  auto checks = check_files(files, options, instance_paths(manifest_, directory_));
  checks.insert(checks.end(), links.begin(), links.end());
  std::sort(checks.begin(), checks.end(),
            [](const FileCheck& a, const FileCheck& b) { return a.file < b.file; });
  std::vector<std::string> extra;
  std::error_code ec;
  for (fs::directory_iterator it(directory_, ec), end; !ec && it != end; it.increment(ec)) {
    const auto name = it->path().filename().string();
    if (is_reserved_store_name(name)) continue;
    if (!manifest_.find(name)) extra.push_back(name);
  }
  if (ec) throw Error(ErrorCode::io, directory_.string() + ": cannot list: " + ec.message());
  std::sort(extra.begin(), extra.end());
  for (const auto& name : extra)
    checks.push_back({name,
                      directory_ / name,
                      {{"extra", (directory_ / name).string() + ": not listed in the manifest"}},
                      {}});
  return checks;
}

StoreInstance Store::instance(std::string_view name) const {
  const ManifestEntry* found = nullptr;
  std::string view;
  std::vector<std::string> candidates;
  if (const auto slash = name.find('/'); slash != std::string_view::npos) {
    const auto benchmark = name.substr(0, slash);
    view = std::string(name.substr(slash + 1));
    for (const auto& e : manifest_.entries)
      if (!e.solutions && e.benchmark == benchmark &&
          std::find(e.views.begin(), e.views.end(), view) != e.views.end())
        candidates.push_back(e.file), found = &e;
  } else {
    for (const auto& e : manifest_.entries)
      if (!e.solutions && std::find(e.views.begin(), e.views.end(), name) != e.views.end())
        candidates.push_back(e.file), found = &e;
    if (!candidates.empty()) {
      view = std::string(name);
    } else {
      for (const auto& e : manifest_.entries)
        if (!e.solutions && e.benchmark == name) candidates.push_back(e.file), found = &e;
      if (found != nullptr && candidates.size() == 1 && found->views.size() == 1)
        view = found->views.front();
    }
  }
  const auto label = directory_.string() + ": '" + std::string(name) + "'";
  if (candidates.empty())
    throw Error(ErrorCode::not_found,
                label +
                    ": no entry serves this benchmark or view (give BENCHMARK, VIEW or "
                    "BENCHMARK/VIEW; mosb store list shows them)");
  if (candidates.size() > 1) {
    std::string files;
    for (const auto& f : candidates) files += (files.empty() ? "" : ", ") + f;
    throw Error(ErrorCode::not_found,
                label + " is ambiguous: served by " + files + " (use BENCHMARK/VIEW)");
  }
  refuse_symlink(directory_ / found->file);
  auto [reader, path] =
      found->packed ? open_packed(directory_, *found)
                    : std::pair{GraphReader::open(directory_ / found->file, VerifyLevel::full),
                                directory_ / found->file};
  StoreInstance out{std::move(reader), *found, std::move(path), std::nullopt, ""};
  if (out.reader.digest() != found->digest)
    throw Error(ErrorCode::damaged, out.path.string() + ": content digest " + out.reader.digest() +
                                        ", the manifest says " + found->digest +
                                        "; run mosb store verify");
  if (!view.empty()) {
    out.view = out.reader.view(view);
    out.query_set = out.view->query_set;
  }
  return out;
}

Store::References Store::references(const std::set<std::string>& instance_digests) const {
  References out;
  std::set<std::string> found;
  std::vector<const ManifestEntry*> listed;
  for (const auto& e : manifest_.entries)
    if (e.solutions && e.solutions->epsilon == "0" &&
        instance_digests.contains(e.solutions->instance))
      listed.push_back(&e);
  // Each file against its entry, on every core: the check is the SHA-256 pass.
  std::vector<std::string> differs(listed.size());
  parallel_for(listed.size(), thread_count(0), [&](std::size_t i) {
    const auto& e = *listed[i];
    const auto path = directory_ / e.file;
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0)
      differs[i] = std::string("cannot read: ") + std::strerror(errno);
    else if (!S_ISREG(st.st_mode))
      differs[i] = "not a regular file (a symbolic link is not followed)";
    else if (static_cast<std::uint64_t>(st.st_size) != e.size)
      differs[i] =
          std::to_string(st.st_size) + " bytes, the manifest says " + std::to_string(e.size);
    else if (const auto sha = sha256_file(path); sha != e.sha256)
      differs[i] = "SHA-256 " + sha + ", the manifest says " + e.sha256;
  });
  for (std::size_t i = 0; i < listed.size(); ++i) {
    const auto path = directory_ / listed[i]->file;
    if (!differs[i].empty())
      throw Error(ErrorCode::damaged, path.string() + ": " + differs[i] +
                                          "; not used as a reference (mosb store verify)");
    out.files.push_back(path);
    found.insert(listed[i]->solutions->instance);
  }
  std::set_difference(instance_digests.begin(), instance_digests.end(), found.begin(), found.end(),
                      std::back_inserter(out.missing));
  return out;
}

std::filesystem::path Store::unpack(std::string_view file) const {
  const auto* e = manifest_.find(file);
  if (e == nullptr || !e->packed)
    throw Error(ErrorCode::not_found, directory_.string() + ": '" + std::string(file) +
                                          "' is not a packed entry of the store");
  refuse_symlink(directory_ / e->file);
  auto copy = directory_ / kCacheDirectory / e->file;
  if (open_packed(directory_, *e).second != copy)
    throw Error(ErrorCode::io, copy.string() +
                                   ": cannot unpack there (the store cannot be written, or "
                                   "something else is in the way)");
  return copy;
}

}  // namespace mosb
