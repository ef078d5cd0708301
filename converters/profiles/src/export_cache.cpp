#include "mosb/converters/export_cache.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <optional>
#include <random>
#include <sstream>
#include <system_error>
#include <utility>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/read_file.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/internal/xxh3.hpp"

namespace mosb::converters {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kManifest = "export.txt";
constexpr std::string_view kLayout = "mosb export cache 2";      // bumped when the text changes
constexpr std::string_view kLayoutWords = "mosb export cache ";  // of every layout ever written
// No manifest is near this size; a larger export.txt (or /dev/zero in its place) is not read.
constexpr std::size_t kManifestCap = std::size_t{1} << 20;

std::mutex g_warning_mutex;
std::function<void(const std::string&)> g_warning;

void warn(const std::string& line) {
  std::lock_guard lock(g_warning_mutex);
  if (g_warning) return g_warning(line);
  std::cerr << "mosb: warning: " << escape_for_terminal(line) << '\n';
}

std::string errno_text() {
  return std::error_code(errno, std::system_category()).message();
}

// A file descriptor, closed when it goes.
class Fd {
 public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  Fd(Fd&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  Fd& operator=(Fd&&) = delete;
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  int get() const { return fd_; }
  explicit operator bool() const { return fd_ >= 0; }

 private:
  int fd_;
};

std::string hex64(std::uint64_t value) {
  static const char digits[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4) out[static_cast<std::size_t>(i)] = digits[value & 15];
  return out;
}

bool is_hex(std::string_view s) {
  return !s.empty() && s.find_first_not_of("0123456789abcdef") == std::string_view::npos;
}

template <class T>
bool parse_number(std::string_view text, T& value) {
  const auto end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  return ec == std::errc() && ptr == end && !text.empty();
}

// Everything the text depends on, one line each: the directory's name is its hash, and the
// manifest repeats it (a hash collision is then a miss, never another export).
std::string export_key(const std::string& digest, const DimacsExportOptions& o) {
  std::ostringstream key;
  key << kLayout << "\ninstance " << digest << "\nview " << o.selection.view << "\nobjectives";
  for (const auto& name : o.selection.objectives) key << " " << name;
  key << "\nqueries " << o.selection.queries << "\nid_base " << (o.id_base ? *o.id_base : 9)
      << "\nmulti_column " << o.multi_column << "\npad_columns " << o.pad_columns
      << "\nqueries_format " << kQueriesFormatNames.name(o.queries_format) << "\ninteger_costs "
      << o.integer_costs << "\nscale " << format_real_cost(o.scale) << "\nmax_arc_cost "
      << (o.max_arc_cost ? std::to_string(*o.max_arc_cost) : "none") << "\nmax_degree "
      << (o.max_degree ? std::to_string(*o.max_degree) : "none") << "\ncollapse "
      << o.collapse_parallel_arcs << "\ndummy_arc " << o.append_dummy_arc << "\ncoordinates "
      << o.coordinates << "\n";
  return key.str();
}

std::uint64_t hash_of(std::string_view text) {
  return XXH3_64bits(text.data(), text.size());
}

// An entry's name: DIGEST16-KEYHASH (16 hex digits each).
std::string entry_name(const std::string& digest, const std::string& key) {
  return digest.substr(0, 16) + "-" + hex64(hash_of(key));
}

bool is_entry_name(std::string_view name) {
  return name.size() == 33 && name[16] == '-' && is_hex(name.substr(0, 16)) &&
         is_hex(name.substr(17));
}

// A temporary's name: .tmp-PID-RANDOM16.
std::string temporary_name() {
  std::random_device random;
  return ".tmp-" + std::to_string(::getpid()) + "-" +
         hex64((std::uint64_t{random()} << 32) ^ random());
}

// The PID in a temporary's name; nullopt for any other name.
std::optional<pid_t> temporary_pid(std::string_view name) {
  if (name.substr(0, 5) != ".tmp-" || name.size() < 5 + 2 + 16 || name[name.size() - 17] != '-' ||
      !is_hex(name.substr(name.size() - 16)))
    return std::nullopt;
  pid_t pid = 0;
  if (!parse_number(name.substr(5, name.size() - 5 - 17), pid) || pid <= 0) return std::nullopt;
  return pid;
}

// `name` in the directory `dir` opened for reading, when it is a regular file: never following a
// link, never blocking on a FIFO, never opening a device (lstat first; fstat again after, for a
// swap in between). Otherwise an invalid Fd and `why` says what it is.
Fd open_regular(int dir, const std::string& name, struct stat& st, std::string& why) {
  why.clear();
  if (::fstatat(dir, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0)
    why = errno == ENOENT ? "missing" : errno_text();
  else if (S_ISLNK(st.st_mode))
    why = "a symbolic link";
  else if (!S_ISREG(st.st_mode))
    why = "not a regular file";
  if (!why.empty()) return Fd();
  Fd fd(::openat(dir, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
  if (!fd)
    why = errno == ELOOP ? "a symbolic link" : errno_text();
  else if (::fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode))
    why = "not a regular file";
  return why.empty() ? std::move(fd) : Fd();
}

// `fd`'s content, read no further than just past `cap` bytes (so a longer file shows as longer
// than `cap`); nullopt on a read error.
std::optional<std::string> read_at_most(int fd, std::size_t cap) {
  std::string text;
  std::array<char, std::size_t{1} << 16> buffer;
  try {
    read_chunks(fd, {}, buffer, [&](const char* data, std::size_t n) {
      text.append(data, n);
      return text.size() <= cap;
    });
  } catch (const Error&) {
    return std::nullopt;
  }
  return text;
}

struct Content {
  std::uint64_t size = 0;
  std::uint64_t hash = 0;  // XXH3-64
};

// The size and XXH3-64 of `fd`'s content, read no further than `limit` bytes (a file that grows
// while it is read is never followed far); nullopt on a read error.
std::optional<Content> content_of(int fd, std::uint64_t limit = UINT64_MAX) {
  Xxh3Stream hash;
  std::vector<char> buffer(std::size_t{1} << 20);
  Content c;
  try {
    read_chunks(fd, {}, buffer, [&](const char* data, std::size_t n) {
      const auto kept = std::min<std::uint64_t>(n, limit - c.size);
      hash.update(data, static_cast<std::size_t>(kept));
      c.size += kept;
      return c.size < limit;
    });
  } catch (const Error&) {
    return std::nullopt;
  }
  c.hash = hash.digest();
  return c;
}

// A file of an export as its manifest records it: `ROLE NAME SIZE XXH3 [SET]`.
struct FileRecord {
  std::string role, name, set;
  Content content;
};

struct Manifest {
  DimacsExportFiles files;
  std::vector<FileRecord> records;
};

// The manifest: the key, `--`, a line per file, the text's counts, and last `check XXH3` of all
// before it (so a manifest edited or cut short is damaged, never an export of fewer files).
std::string manifest_text(const std::string& key, const DimacsExportFiles& f) {
  std::ostringstream out;
  out << key << "--\n";
  const auto line = [&](const char* role, const fs::path& path, const std::string& set = {}) {
    struct stat st {};
    std::string why;
    const auto fd = open_regular(AT_FDCWD, path.string(), st, why);
    const auto content = fd ? content_of(fd.get()) : std::nullopt;
    if (!content)
      throw Error(ErrorCode::io, path.string() + ": cannot read the export back: " +
                                     (why.empty() ? errno_text() : why));
    out << role << " " << path.filename().string() << " " << content->size << " "
        << hex64(content->hash) << (set.empty() ? "" : " " + set) << "\n";
  };
  for (const auto& path : f.objectives) line("objective", path);
  if (!f.multi_column.empty()) line("multi_column", f.multi_column);
  if (!f.coordinates.empty()) line("coordinates", f.coordinates);
  for (const auto& [set, path] : f.queries) line("queries", path, set);
  out << "vertices " << f.vertex_count << "\narcs " << f.arc_count << "\nid_base " << f.id_base
      << "\nscaled";
  for (const auto& name : f.scaled_objectives) out << " " << name;
  out << "\n";
  const auto text = out.str();
  return text + "check " + hex64(hash_of(text)) + "\n";
}

// A file name of an entry's own: no directory part, not the manifest.
bool is_plain_name(const std::string& name) {
  return !name.empty() && name != "." && name != ".." && name != kManifest &&
         name.find('/') == std::string::npos;
}

// One manifest line's words into `m`; false when they are not a line this code writes.
bool parse_line(const std::vector<std::string>& w, const fs::path& dir, Manifest& m) {
  auto& f = m.files;
  if (w.empty()) return false;
  const auto& role = w[0];
  if (role == "vertices" && w.size() == 2) return parse_number(w[1], f.vertex_count);
  if (role == "arcs" && w.size() == 2) return parse_number(w[1], f.arc_count);
  if (role == "id_base" && w.size() == 2) return parse_number(w[1], f.id_base);
  if (role == "scaled") {
    f.scaled_objectives.assign(w.begin() + 1, w.end());
    return true;
  }
  const bool queries = role == "queries";
  if ((role != "objective" && role != "multi_column" && role != "coordinates" && !queries) ||
      w.size() != (queries ? 5u : 4u))
    return false;
  FileRecord r{role, w[1], queries ? w[4] : "", {}};
  const auto hash_end = w[3].data() + w[3].size();
  if (!is_plain_name(r.name) || !parse_number(w[2], r.content.size) || w[3].size() != 16 ||
      !is_hex(w[3]) || std::from_chars(w[3].data(), hash_end, r.content.hash, 16).ptr != hash_end)
    return false;
  const auto path = dir / r.name;
  f.written.push_back(path);
  if (role == "objective") f.objectives.push_back(path);
  if (role == "multi_column") f.multi_column = path;
  if (role == "coordinates") f.coordinates = path;
  if (queries) f.queries.emplace_back(r.set, path);
  m.records.push_back(std::move(r));
  return true;
}

// The export `text` (the manifest of `dir`) records; nullopt, with `why`, when it is not a whole
// manifest of `key`.
std::optional<Manifest> parse_manifest(std::string_view text, const std::string& key,
                                       const fs::path& dir, std::string& why) {
  const auto last = text.size() < 2 ? std::string_view::npos : text.rfind('\n', text.size() - 2);
  const auto body = text.substr(0, last == std::string_view::npos ? 0 : last + 1);
  if (text.substr(body.size()) != "check " + hex64(hash_of(body)) + "\n") {
    why = "its check line does not match its text (edited or cut short)";
    return std::nullopt;
  }
  if (body.substr(0, key.size()) != key || body.substr(key.size(), 3) != "--\n") {
    why = "it records another export (edited, or a hash collision)";
    return std::nullopt;
  }
  std::istringstream lines(std::string(body.substr(key.size() + 3)));
  Manifest m;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string word; in >> word;) words.push_back(word);
    if (!parse_line(words, dir, m)) {
      why = "a line it does not write: '" + line + "'";
      return std::nullopt;
    }
  }
  return m;
}

// The first thing in the entry `dir` (open as `dir_fd`) that is not a regular file ("PATH: what
// it is"); empty when there is none.
std::string odd_file(int dir_fd, const fs::path& dir) {
  const int own = ::openat(dir_fd, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  DIR* listing = own < 0 ? nullptr : ::fdopendir(own);
  if (!listing) {
    auto why = dir.string() + ": " + errno_text();
    if (own >= 0) ::close(own);
    return why;
  }
  std::string why;
  while (const dirent* e = ::readdir(listing)) {
    const std::string name = e->d_name;
    struct stat st {};
    if (name == "." || name == ".." || ::fstatat(dir_fd, e->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0)
      continue;
    if (!S_ISREG(st.st_mode)) {
      why = (dir / name).string() +
            (S_ISLNK(st.st_mode) ? ": a symbolic link" : ": not a regular file");
      break;
    }
  }
  ::closedir(listing);
  return why;
}

// Why the files `m` records are not as they were written into the entry `dir` (open as
// `dir_fd`); empty when they are.
std::string check_files(int dir_fd, const fs::path& dir, const Manifest& m) {
  for (const auto& r : m.records) {
    struct stat st {};
    std::string why;
    const auto fd = open_regular(dir_fd, r.name, st, why);
    const auto where = (dir / r.name).string() + ": ";
    if (!fd) return where + why;
    if (static_cast<std::uint64_t>(st.st_size) != r.content.size)
      return where + std::to_string(st.st_size) + " bytes, " + std::string(kManifest) + " says " +
             std::to_string(r.content.size);
    const auto content = content_of(fd.get(), r.content.size + 1);
    if (!content) return where + errno_text();
    if (content->size != r.content.size || content->hash != r.content.hash)
      return where + "its content changed since it was exported (XXH3-64 " + hex64(content->hash) +
             ", " + std::string(kManifest) + " says " + hex64(r.content.hash) + ")";
  }
  return odd_file(dir_fd, dir);
}

// An entry as found: its files when whole, else what is wrong ("PATH: why"; empty: no entry).
struct Found {
  std::optional<DimacsExportFiles> files;
  std::string damage;
};

Found look_up(const fs::path& dir, const std::string& key) {
  const Fd dir_fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (!dir_fd && errno == ENOENT) return {};
  if (!dir_fd)
    return {std::nullopt,
            dir.string() + ": " +
                (errno == ELOOP || errno == ENOTDIR ? "not a directory (a symbolic link or a file)"
                                                    : errno_text())};
  const auto file = (dir / kManifest).string() + ": ";
  struct stat st {};
  std::string why;
  const auto manifest = open_regular(dir_fd.get(), std::string(kManifest), st, why);
  if (!manifest) return {std::nullopt, file + why};
  const auto text = read_at_most(manifest.get(), kManifestCap);
  if (!text) return {std::nullopt, file + errno_text()};
  if (text->size() > kManifestCap) return {std::nullopt, file + "larger than 1 MiB"};
  auto m = parse_manifest(*text, key, dir, why);
  if (!m) return {std::nullopt, file + why};
  if (why = check_files(dir_fd.get(), dir, *m); !why.empty()) return {std::nullopt, why};
  return {std::move(m->files), {}};
}

// Lets this user remove the directory `path` it made read-only (never through a symlink).
void make_removable(const fs::path& path) {
  const Fd fd(::open(path.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (fd) ::fchmod(fd.get(), 0700);
}

std::error_code remove_tree(const fs::path& path) {
  make_removable(path);
  std::error_code ec;
  fs::remove_all(path, ec);  // removes a symlink inside, never what it points to
  return ec;
}

// Makes the finished export in `temporary` read-only, so that a solver run as another user
// cannot change it (this user's own solvers are caught by the hashes).
void seal(const fs::path& temporary, const DimacsExportFiles& files) {
  for (const auto& path : files.written) ::chmod(path.c_str(), 0444);
  ::chmod((temporary / kManifest).c_str(), 0444);
  ::chmod(temporary.c_str(), 0555);
}

// Renames `from` to `to` unless something is at `to` (false, errno EEXIST); where the file
// system cannot say so in one step, checks first.
bool rename_noreplace(const fs::path& from, const fs::path& to) {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return true;
  if (errno != EINVAL && errno != ENOSYS) return false;
  struct stat st {};
  if (::lstat(to.c_str(), &st) == 0) {
    errno = EEXIST;
    return false;
  }
  return ::rename(from.c_str(), to.c_str()) == 0;
}

// Places the finished export `temporary` at `dir`, whose manifest is `manifest`; its files. A
// whole entry another run placed first is kept (and `temporary` removed); a damaged one is
// swapped out in one step (RENAME_EXCHANGE: a concurrent reader never finds the name missing)
// and removed.
DimacsExportFiles place(const fs::path& temporary, const fs::path& dir, const std::string& key,
                        const std::string& manifest) {
  std::string why;
  const auto ours = [&] { return std::move(parse_manifest(manifest, key, dir, why)->files); };
  if (rename_noreplace(temporary, dir)) return ours();
  const int error = errno;
  const Error cannot(ErrorCode::io,
                     dir.string() + ": cannot place the export in the cache: " + errno_text());
  if (error != EEXIST && error != ENOTEMPTY) {
    remove_tree(temporary);
    throw cannot;
  }
  if (auto found = look_up(dir, key); found.files) {
    remove_tree(temporary);
    return std::move(*found.files);
  }
  if (::renameat2(AT_FDCWD, temporary.c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) == 0) {
    remove_tree(temporary);  // now the damaged entry
    return ours();
  }
  // No exchange on this file system: the damaged entry is moved aside first.
  const auto aside = dir.parent_path() / temporary_name();
  if (::rename(dir.c_str(), aside.c_str()) == 0) remove_tree(aside);
  if (rename_noreplace(temporary, dir)) return ours();
  remove_tree(temporary);
  if (auto found = look_up(dir, key); found.files) return std::move(*found.files);
  throw cannot;
}

bool process_alive(pid_t pid) {
  return ::kill(pid, 0) == 0 || errno == EPERM;
}

// Whether `dir` (a real directory) holds an export.txt, a regular file, whose first line is a
// layout line this code writes: the mark of an export of this cache, of any version.
bool has_layout_line(const fs::path& dir) {
  const Fd dir_fd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  struct stat st {};
  std::string why;
  const auto manifest = dir_fd ? open_regular(dir_fd.get(), std::string(kManifest), st, why) : Fd();
  const auto head = manifest ? read_at_most(manifest.get(), 64) : std::nullopt;
  if (!head) return false;
  const auto line = std::string_view(*head).substr(0, head->find('\n'));
  unsigned version = 0;
  return head->find('\n') != std::string::npos &&
         line.substr(0, kLayoutWords.size()) == kLayoutWords &&
         parse_number(line.substr(kLayoutWords.size()), version);
}

// Why `path` in the cache is not removed by `cache clear`; empty when it is the cache's own.
std::string reason_to_keep(const fs::path& path) {
  const auto name = path.filename().string();
  struct stat st {};
  const bool directory = ::lstat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
  if (directory && is_entry_name(name) && has_layout_line(path)) return {};
  const auto pid = temporary_pid(name);
  if (!directory || !pid || st.st_uid != ::geteuid()) return "not an export of mosb";
  if (*pid != ::getpid() && process_alive(*pid))
    return "being written by a running process (" + std::to_string(*pid) + ")";
  return {};
}

}  // namespace

void set_export_cache_warning_handler(std::function<void(const std::string&)> handler) {
  std::lock_guard lock(g_warning_mutex);
  g_warning = std::move(handler);
}

fs::path default_export_cache() {
  if (const char* dir = std::getenv("MOSB_EXPORT_CACHE"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "mosb" / "exports";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "mosb" / "exports";
  throw Error(ErrorCode::invalid_argument,
              {"no export cache: set MOSB_EXPORT_CACHE, XDG_CACHE_HOME or HOME, or give ",
               setting("export_cache"), " DIR"});
}

CachedExport cached_export(const fs::path& cache, const fs::path& instance,
                           const std::string& digest, const DimacsExportOptions& options) {
  const auto key = export_key(digest, options);
  CachedExport out;
  out.directory = cache / entry_name(digest, key);
  auto found = look_up(out.directory, key);
  if (found.files) {
    out.files = std::move(*found.files);
    out.reused = true;
    return out;
  }
  if (!found.damage.empty()) warn("export cache: " + found.damage + "; exported again");
  std::error_code ec;
  fs::create_directories(cache, ec);
  if (ec)
    throw Error(ErrorCode::io,
                cache.string() + ": cannot create the export cache: " + ec.message());
  const auto temporary = cache / temporary_name();
  DimacsExportOptions o = options;
  o.out_dir = temporary;
  std::string manifest;
  try {
    const auto files = export_dimacs_files(instance, o);
    manifest = manifest_text(key, files);
    AtomicFile file(temporary / kManifest);
    file.write(manifest.data(), manifest.size());
    file.commit();
    seal(temporary, files);
  } catch (...) {
    remove_tree(temporary);
    throw;
  }
  out.files = place(temporary, out.directory, key, manifest);
  return out;
}

ClearedExports clear_export_cache(const fs::path& cache) {
  std::error_code ec;
  ClearedExports out;
  if (!fs::exists(cache, ec)) return out;
  for (const auto& entry : fs::directory_iterator(cache, ec)) {
    if (const auto why = reason_to_keep(entry.path()); !why.empty()) {
      out.left.push_back(entry.path().string() + ": " + why + ", left alone");
      continue;
    }
    if (const auto failed = remove_tree(entry.path()))
      throw Error(ErrorCode::io, entry.path().string() + ": cannot remove: " + failed.message());
    ++out.removed;
  }
  if (ec)
    throw Error(ErrorCode::io, cache.string() + ": cannot read the directory: " + ec.message());
  return out;
}

}  // namespace mosb::converters
