#include "mosb/converters/export_cache.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <random>
#include <sstream>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/xxh3.hpp"

namespace mosb::converters {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kManifest = "export.txt";
constexpr std::string_view kLayout = "mosb export cache 1";  // bumped when the text changes

std::string hex64(std::uint64_t value) {
  static const char digits[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 15; i >= 0; --i, value >>= 4) out[static_cast<std::size_t>(i)] = digits[value & 15];
  return out;
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

std::uint64_t hash_of(const std::string& text) {
  return XXH3_64bits(text.data(), text.size());
}

// The manifest: the key, then `ROLE NAME SIZE [SET]` per file and the text's counts.
std::string manifest_text(const std::string& key, const DimacsExportFiles& f) {
  std::ostringstream out;
  out << key << "--\n";
  const auto line = [&](const char* role, const fs::path& path, const std::string& set = {}) {
    out << role << " " << path.filename().string() << " " << fs::file_size(path)
        << (set.empty() ? "" : " " + set) << "\n";
  };
  for (const auto& path : f.objectives) line("objective", path);
  if (!f.multi_column.empty()) line("multi_column", f.multi_column);
  if (!f.coordinates.empty()) line("coordinates", f.coordinates);
  for (const auto& [set, path] : f.queries) line("queries", path, set);
  out << "vertices " << f.vertex_count << "\narcs " << f.arc_count << "\nid_base " << f.id_base
      << "\nscaled";
  for (const auto& name : f.scaled_objectives) out << " " << name;
  out << "\n";
  return out.str();
}

// The export a manifest describes, when every file is there with its size; nullopt otherwise.
std::optional<DimacsExportFiles> read_manifest(const fs::path& dir, const std::string& key) {
  std::ifstream in(dir / kManifest, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream all;
  all << in.rdbuf();
  const auto text = all.str();
  if (text.compare(0, key.size(), key) != 0 || text.compare(key.size(), 3, "--\n") != 0)
    return std::nullopt;
  std::istringstream lines(text.substr(key.size() + 3));
  DimacsExportFiles f;
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string role, name, set;
    std::uint64_t size = 0;
    words >> role;
    if (role == "vertices" || role == "arcs" || role == "id_base") {
      std::uint64_t value = 0;
      words >> value;
      if (role == "vertices") f.vertex_count = value;
      if (role == "arcs") f.arc_count = value;
      if (role == "id_base") f.id_base = static_cast<unsigned>(value);
      continue;
    }
    if (role == "scaled") {
      while (words >> name) f.scaled_objectives.push_back(name);
      continue;
    }
    words >> name >> size >> set;
    const auto path = dir / name;
    std::error_code ec;
    if (name.empty() || fs::file_size(path, ec) != size || ec) return std::nullopt;
    f.written.push_back(path);
    if (role == "objective") f.objectives.push_back(path);
    if (role == "multi_column") f.multi_column = path;
    if (role == "coordinates") f.coordinates = path;
    if (role == "queries") f.queries.emplace_back(set, path);
  }
  return f;
}

std::string temporary_name() {
  std::random_device random;
  return ".tmp-" + std::to_string(::getpid()) + "-" +
         hex64((std::uint64_t{random()} << 32) ^ random());
}

}  // namespace

fs::path default_export_cache() {
  if (const char* dir = std::getenv("MOSB_EXPORT_CACHE"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return fs::path(xdg) / "mosb" / "exports";
  if (const char* home = std::getenv("HOME"); home && *home)
    return fs::path(home) / ".cache" / "mosb" / "exports";
  throw Error(ErrorCode::invalid_argument,
              "no export cache: set MOSB_EXPORT_CACHE, XDG_CACHE_HOME or HOME, or give "
              "--export-cache DIR");
}

CachedExport cached_export(const fs::path& cache, const fs::path& instance,
                           const std::string& digest, const DimacsExportOptions& options) {
  const auto key = export_key(digest, options);
  CachedExport out;
  out.directory = cache / (digest.substr(0, 16) + "-" + hex64(hash_of(key)));
  if (auto found = read_manifest(out.directory, key)) {
    out.files = std::move(*found);
    out.reused = true;
    return out;
  }
  std::error_code ec;
  fs::create_directories(cache, ec);
  if (ec)
    throw Error(ErrorCode::io,
                cache.string() + ": cannot create the export cache: " + ec.message());
  const auto temporary = cache / temporary_name();
  DimacsExportOptions o = options;
  o.out_dir = temporary;
  try {
    out.files = export_dimacs_files(instance, o);
    AtomicFile manifest(temporary / kManifest);
    manifest.write(manifest_text(key, out.files));
    manifest.commit();
  } catch (...) {
    fs::remove_all(temporary, ec);
    throw;
  }
  // A damaged export (a file gone or cut short) is replaced; one another run just placed is used.
  if (fs::exists(out.directory) && !read_manifest(out.directory, key))
    fs::remove_all(out.directory, ec);
  fs::rename(temporary, out.directory, ec);
  if (ec) {
    fs::remove_all(temporary, ec);
    if (auto found = read_manifest(out.directory, key)) {
      out.files = std::move(*found);
      return out;
    }
    throw Error(ErrorCode::io, out.directory.string() + ": cannot place the export in the cache");
  }
  out.files = *read_manifest(out.directory, key);
  return out;
}

std::uint64_t clear_export_cache(const fs::path& cache) {
  std::error_code ec;
  if (!fs::exists(cache, ec)) return 0;
  std::uint64_t removed = 0;
  for (const auto& entry : fs::directory_iterator(cache, ec)) {
    const bool export_dir = fs::exists(entry.path() / kManifest) ||
                            entry.path().filename().string().rfind(".tmp-", 0) == 0;
    if (!export_dir) continue;  // not ours: left alone
    fs::remove_all(entry.path(), ec);
    if (ec) throw Error(ErrorCode::io, entry.path().string() + ": cannot remove: " + ec.message());
    ++removed;
  }
  if (ec)
    throw Error(ErrorCode::io, cache.string() + ": cannot read the directory: " + ec.message());
  return removed;
}

}  // namespace mosb::converters
