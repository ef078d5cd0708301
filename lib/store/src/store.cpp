#include "mosb/store.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <mutex>
#include <set>
#include <thread>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/hex.hpp"
#include "mosb/internal/xxh3.hpp"
#include "mosb/pack.hpp"
#include "mosb/sha256.hpp"
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
    for (;;) {
      const ssize_t got = ::read(fd, buffer.data(), buffer.size());
      if (got < 0) {
        if (errno == EINTR) continue;
        throw Error(ErrorCode::io, path.string() + ": cannot read: " + std::strerror(errno));
      }
      if (got == 0) return;
      consume(buffer.data(), static_cast<std::size_t>(got));
    }
  }
  int fd;
};

FileCheck check_one(const ManifestEntry& e, const fs::path& path) {
  FileCheck c{e.file, path, {}};
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
    const auto reader = GraphReader::open(path);
    const auto digest = reader.digest();
    if (digest != e.digest)
      problem("wrong-digest", "content digest " + digest + ", the manifest says " + e.digest);
    // A packed file is checked as it will be used: unpacked (every frame decoded and checked
    // against its section checksum), then verified in full.
    const auto checked = is_packed(reader.header()) ? mosb::load(path) : reader;
    if (const auto found = verify(checked, VerifyLevel::full)) problem("damaged", *found);
  } catch (const Error& error) {
    c.problems.push_back({error.code() == ErrorCode::io ? "unreadable" : "damaged", error.what()});
  }
  return c;
}

unsigned worker_count(unsigned asked, std::size_t jobs) {
  unsigned threads = asked ? asked : std::max(1u, std::thread::hardware_concurrency());
  return static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(1, jobs)));
}

void copy_into(const fs::path& source, AtomicFile& out) {
  InputFd in(source);
  in.read_all(source, [&](const char* data, std::size_t size) { out.write(data, size); });
}

// The reader of a packed entry: its unpacked copy in DIR/.cache, made first when absent or not
// the entry's content (a damaged or an earlier version's copy), or, when the store cannot be
// written, the packed file unpacked into memory.
std::pair<GraphReader, fs::path> open_packed(const fs::path& directory, const ManifestEntry& e) {
  const auto packed = directory / e.file;
  const auto cache = directory / kCacheDirectory;
  const auto copy = cache / e.file;
  std::error_code ec;
  if (fs::exists(copy, ec)) {
    try {
      auto reader = GraphReader::open(copy, VerifyLevel::full);
      if (reader.digest() == e.digest) return {std::move(reader), copy};
    } catch (const Error&) {
      // Made again below from the packed file, which is checked as it is unpacked.
    }
  }
  // A read-only store, or a directory where the copy belongs (rename cannot replace it, and the
  // store does not delete what it did not make): decoded into memory, nothing written.
  if (::access((fs::is_directory(cache, ec) ? cache : directory).c_str(), W_OK) != 0 ||
      fs::is_directory(copy, ec))
    return {mosb::load(packed, VerifyLevel::full), packed};
  fs::create_directory(cache, ec);
  if (ec) throw Error(ErrorCode::io, cache.string() + ": cannot create the cache: " + ec.message());
  unpack_file(packed, copy);
  return {GraphReader::open(copy, VerifyLevel::full), copy};
}

}  // namespace

std::vector<FileCheck> check_files(const std::vector<std::pair<ManifestEntry, fs::path>>& files,
                                   const CheckOptions& options) {
  std::vector<FileCheck> checks(files.size());
  std::atomic<std::size_t> next{0};
  std::mutex progress_mutex;
  std::size_t done = 0;
  report(options.progress, "verify", 0, files.size());
  auto work = [&] {
    for (std::size_t i = next++; i < files.size(); i = next++) {
      try {
        checks[i] = check_one(files[i].first, files[i].second);
      } catch (const std::exception& error) {  // bad_alloc, filesystem_error: a report, not a crash
        checks[i] = {files[i].first.file, files[i].second, {{"unreadable", error.what()}}};
      }
      std::lock_guard lock(progress_mutex);
      report(options.progress, "verify", ++done, files.size());
    }
  };
  {
    std::vector<std::jthread> pool;
    const unsigned threads = worker_count(options.threads, files.size());
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
    work();
  }
  return checks;
}

std::vector<FileCheck> check_against_manifest(const fs::path& manifest_path,
                                              const std::vector<fs::path>& paths,
                                              const CheckOptions& options) {
  const auto manifest = read_manifest(manifest_path);
  std::vector<std::pair<ManifestEntry, fs::path>> files;
  std::vector<FileCheck> unlisted;
  if (paths.empty()) {
    for (const auto& e : manifest.entries)
      files.emplace_back(e, manifest_path.parent_path() / e.file);
  } else {
    for (const auto& path : paths) {
      const auto name = path.filename().string();
      if (const auto* e = manifest.find(name))
        files.emplace_back(*e, path);
      else
        unlisted.push_back(
            {name, path, {{"extra", path.string() + ": not listed in " + manifest_path.string()}}});
    }
  }
  auto checks = check_files(files, options);
  checks.insert(checks.end(), unlisted.begin(), unlisted.end());
  return checks;
}

std::string xxh3_file(const fs::path& path) {
  InputFd in(path);
  std::unique_ptr<XXH3_state_t, decltype(&XXH3_freeState)> state(XXH3_createState(),
                                                                 &XXH3_freeState);
  if (!state) throw Error(path.string() + ": out of memory");
  XXH3_64bits_reset(state.get());
  in.read_all(path, [&](const char* data, std::size_t size) {
    XXH3_64bits_update(state.get(), data, size);
  });
  return hex64(XXH3_64bits_digest(state.get()));
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
      c.problem =
          instance.display_name() + ": raw input name '" + input.name + "' is not a base name";
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
  return {directory, read_manifest(path)};
}

std::vector<ManifestEntry> Store::add(const std::vector<fs::path>& files,
                                      const AddOptions& options) {
  // Everything is checked before anything the manifest lists is written.
  std::vector<ManifestEntry> added;
  std::vector<fs::path> stored_from = files;  // where each file's stored bytes come from
  std::vector<bool> staged(files.size(), false);
  std::set<std::string> names;
  const auto staging = directory_ / kStagingDirectory;
  // Packed copies not placed (an add that fails) are removed; the staging directory too when empty.
  struct StagingCleanup {
    const std::vector<fs::path>& paths;
    const std::vector<bool>& staged;
    fs::path directory;
    ~StagingCleanup() {
      std::error_code ec;
      for (std::size_t i = 0; i < paths.size(); ++i)
        if (staged[i]) fs::remove(paths[i], ec);
      fs::remove(directory, ec);  // fails, harmlessly, while a concurrent add still uses it
    }
  } cleanup{stored_from, staged, staging};
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto& source = files[i];
    auto entry = describe_file(source);
    // A packed file is decoded (every frame checked) and verified like any other.
    const auto reader = entry.packed ? mosb::load(source) : GraphReader::open(source);
    if (const auto problem = mosb::verify(reader, VerifyLevel::full))
      throw Error(ErrorCode::damaged, source.string() + ": file is damaged: " + *problem);
    if (!names.insert(entry.file).second)
      throw Error(source.string() + ": a second file named '" + entry.file + "' in one add");
    if (options.pack && !entry.packed) {
      report(options.progress, "pack", i, files.size());
      std::error_code ec;
      fs::create_directory(staging, ec);
      if (ec) throw Error(ErrorCode::io, staging.string() + ": cannot create: " + ec.message());
      stored_from[i] = staging / entry.file;
      pack_file(source, stored_from[i], *options.pack);
      staged[i] = true;
      entry = describe_file(stored_from[i]);
    }
    if (const auto* listed = manifest_.find(entry.file);
        listed && (listed->sha256.empty() || listed->sha256 != entry.sha256))
      throw Error(source.string() + ": the store already lists a different '" + entry.file + "'");
    added.push_back(std::move(entry));
  }
  if (options.pack) report(options.progress, "pack", files.size(), files.size());
  report(options.progress, "add", 0, files.size());
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto target = directory_ / added[i].file;
    std::error_code ec;
    // A file already in place is adopted where it lies; a rename within one file system is atomic
    // by itself; anything else is copied through a temporary.
    const bool in_place =
        !staged[i] && fs::exists(target, ec) && fs::equivalent(target, files[i], ec);
    bool renamed = false;
    if (!in_place && (options.move || staged[i])) {
      fs::rename(stored_from[i], target, ec);
      renamed = !ec;
    }
    if (!in_place && !renamed) {
      AtomicFile out(target);
      copy_into(stored_from[i], out);
      out.commit();
    }
    report(options.progress, "add", i + 1, files.size());
  }
  // The bytes just placed are the bytes described: a source changed between the check and the
  // copy is caught here, before the manifest names it.
  for (std::size_t i = 0; i < files.size(); ++i)
    if (sha256_file(directory_ / added[i].file) != added[i].sha256)
      throw Error(files[i].string() + ": changed while it was being added");
  Manifest next = manifest_;
  next.legacy = false;
  for (const auto& e : added) {
    auto it = std::find_if(next.entries.begin(), next.entries.end(),
                           [&](const ManifestEntry& x) { return x.file == e.file; });
    if (it != next.entries.end())
      *it = e;
    else
      next.entries.push_back(e);
  }
  std::sort(next.entries.begin(), next.entries.end(),
            [](const auto& a, const auto& b) { return a.file < b.file; });
  write_manifest(manifest_path(), next);
  manifest_ = std::move(next);
  if (options.move)
    for (const auto& source : files) {
      std::error_code ec;
      if (fs::exists(source, ec) && !fs::equivalent(source, directory_ / source.filename(), ec))
        fs::remove(source, ec);
    }
  return added;
}

std::vector<FileCheck> Store::verify(const CheckOptions& options) const {
  std::vector<std::pair<ManifestEntry, fs::path>> files;
  for (const auto& e : manifest_.entries) files.emplace_back(e, directory_ / e.file);
  auto checks = check_files(files, options);
  std::vector<std::string> extra;
  std::error_code ec;
  for (fs::directory_iterator it(directory_, ec), end; !ec && it != end; it.increment(ec)) {
    const auto name = it->path().filename().string();
    if (name == kManifestName || name.starts_with('.')) continue;
    if (!manifest_.find(name)) extra.push_back(name);
  }
  if (ec) throw Error(ErrorCode::io, directory_.string() + ": cannot list: " + ec.message());
  std::sort(extra.begin(), extra.end());
  for (const auto& name : extra)
    checks.push_back({name,
                      directory_ / name,
                      {{"extra", (directory_ / name).string() + ": not listed in the manifest"}}});
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
      if (e.benchmark == benchmark &&
          std::find(e.views.begin(), e.views.end(), view) != e.views.end())
        candidates.push_back(e.file), found = &e;
  } else {
    for (const auto& e : manifest_.entries)
      if (std::find(e.views.begin(), e.views.end(), name) != e.views.end())
        candidates.push_back(e.file), found = &e;
    if (!candidates.empty()) {
      view = std::string(name);
    } else {
      for (const auto& e : manifest_.entries)
        if (e.benchmark == name) candidates.push_back(e.file), found = &e;
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

}  // namespace mosb
