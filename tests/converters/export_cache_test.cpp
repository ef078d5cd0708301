// The export cache (converters/profiles, spec/RUN.md §10.3): an entry whose files are not as
// written (edited in place at the same size, a symlink, a FIFO, missing) is exported again with
// a warning, never read, never waited on; `cache clear` removes only the cache's own entries.
#include "mosb/converters/export_cache.hpp"

#include <doctest/doctest.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "mosb/converters/grid_generator.hpp"
#include "mosb/converters/netmaker_generator.hpp"
#include "mosb/graph_reader.hpp"
#include "temp_dir.hpp"
#include "test_files.hpp"

using namespace mosb;
using namespace mosb::converters;
using namespace mosb::testing;  // TempDir, write_text, slurp
namespace fs = std::filesystem;

namespace {

// A cache holding a fresh Grid's export, the warnings it gave, and what a fresh export reads.
struct CacheFixture {
  TempDir dir;
  fs::path cache = dir / "cache";
  fs::path instance = dir / "g.mosb";
  std::string digest;
  DimacsExportOptions options;
  std::vector<std::string> warnings;
  std::map<std::string, std::string> fresh;  // file name -> text

  CacheFixture() {
    write_graph(generate_grid({12, 9, 2, 5}), instance);
    digest = GraphReader::open(instance).digest();
    set_export_cache_warning_handler([this](const std::string& line) { warnings.push_back(line); });
    const auto first = export_once();
    CHECK(!first.reused);
    fresh = texts(first);
  }
  ~CacheFixture() {
    set_export_cache_warning_handler({});
    clear_export_cache(cache);  // the entries are read-only: TempDir alone cannot remove them
  }
  CachedExport export_once() { return cached_export(cache, instance, digest, options); }
  static std::map<std::string, std::string> texts(const CachedExport& e) {
    std::map<std::string, std::string> out;
    for (const auto& path : e.files.written) out[path.filename().string()] = slurp(path);
    return out;
  }
  fs::path gr() const {
    return cached_export(cache, instance, digest, options).files.objectives.at(0);
  }
  // Another export of the same key: re-exported (with one warning naming `file`) and then the
  // same text as a fresh export.
  void check_reexported(const fs::path& file) {
    warnings.clear();
    const auto again = export_once();
    CHECK(!again.reused);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0].find(file.string()) != std::string::npos);
    CHECK(warnings[0].find('\n') == std::string::npos);
    CHECK(texts(again) == fresh);
    warnings.clear();
    CHECK(export_once().reused);
    CHECK(warnings.empty());
  }
};

// Rewrites one digit of `path` in place, the size unchanged (as root ignores the 0444 mode).
void edit_in_place(const fs::path& path) {
  fs::permissions(path, fs::perms::owner_write, fs::perm_options::add);
  auto text = slurp(path);
  const auto digit = text.find_last_of("123456789");
  text[digit] = text[digit] == '9' ? '8' : static_cast<char>(text[digit] + 1);
  write_text(path, text);
}

}  // namespace

TEST_CASE("export cache: entries are read-only and reused while whole") {
  CacheFixture f;
  const auto e = f.export_once();
  CHECK(e.reused);
  CHECK((fs::status(e.directory).permissions() & fs::perms::all) == fs::perms(0555));
  for (const auto& path : e.files.written)
    CHECK((fs::status(path).permissions() & fs::perms::all) == fs::perms(0444));
  const auto manifest = slurp(e.directory / "export.txt");
  CHECK(manifest.rfind("mosb export cache 2\n", 0) == 0);
  CHECK(manifest.find("\ncheck ") != std::string::npos);
  CHECK(f.warnings.empty());
}

TEST_CASE("export cache: a same-size edit of a cached .gr is exported again") {
  CacheFixture f;
  const auto gr = f.gr();
  const auto size = fs::file_size(gr);
  edit_in_place(gr);
  REQUIRE(fs::file_size(gr) == size);
  REQUIRE(slurp(gr) != f.fresh.at(gr.filename().string()));
  f.check_reexported(gr);
  CHECK(f.warnings.empty());
}

TEST_CASE("export cache: a cached file replaced by a symlink to a same-size file") {
  CacheFixture f;
  const auto gr = f.gr();
  const auto other = f.dir / "other.gr";
  write_text(other, slurp(gr));
  edit_in_place(other);
  fs::permissions(gr.parent_path(), fs::perms::owner_all, fs::perm_options::add);
  fs::remove(gr);
  fs::create_symlink(other, gr);
  f.check_reexported(gr);
  CHECK(fs::exists(other));  // the link was removed, not what it points to
}

TEST_CASE("export cache: a missing file and a manifest that is a FIFO") {
  CacheFixture f;
  const auto gr = f.gr();
  const auto directory = gr.parent_path();
  fs::permissions(directory, fs::perms::owner_all, fs::perm_options::add);
  fs::remove(gr);
  f.check_reexported(gr);
  fs::permissions(directory, fs::perms::owner_all, fs::perm_options::add);
  fs::remove(directory / "export.txt");
  REQUIRE(::mkfifo((directory / "export.txt").c_str(), 0644) == 0);
  const auto start = std::chrono::steady_clock::now();
  f.check_reexported(directory / "export.txt");
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(20));
}

TEST_CASE("export cache: an edited manifest, a stray FIFO in the entry") {
  CacheFixture f;
  const auto directory = f.gr().parent_path();
  const auto manifest = directory / "export.txt";
  fs::permissions(manifest, fs::perms::owner_write, fs::perm_options::add);
  auto text = slurp(manifest);
  text.replace(text.find("\nvertices "), 10, "\nvertices 1");
  write_text(manifest, text);
  f.check_reexported(manifest);
  fs::permissions(directory, fs::perms::owner_all, fs::perm_options::add);
  REQUIRE(::mkfifo((directory / "stray").c_str(), 0644) == 0);
  f.check_reexported(directory / "stray");
}

TEST_CASE("export cache: the entry itself a symlink to a whole copy, a device as export.txt") {
  CacheFixture f;
  const auto directory = f.gr().parent_path();
  const auto copy = f.dir / "copy";
  fs::create_directory(copy);
  for (const auto& entry : fs::directory_iterator(directory))
    fs::copy_file(entry.path(), copy / entry.path().filename());
  fs::permissions(directory, fs::perms::owner_all, fs::perm_options::add);
  fs::remove_all(directory);
  fs::create_directory_symlink(copy, directory);
  f.check_reexported(directory);
  CHECK(fs::exists(copy / "export.txt"));  // the link was removed, not what it points to
  if (::geteuid() == 0) {                  // /dev/zero's device: never read (it would never end)
    fs::permissions(directory, fs::perms::owner_all, fs::perm_options::add);
    fs::remove(directory / "export.txt");
    REQUIRE(::mknod((directory / "export.txt").c_str(), S_IFCHR | 0444, ::makedev(1, 5)) == 0);
    f.check_reexported(directory / "export.txt");
  }
}

TEST_CASE("export cache: runs at once on a damaged entry all get the whole export") {
  CacheFixture f;
  const auto gr = f.gr();
  edit_in_place(gr);
  std::vector<std::map<std::string, std::string>> seen(4);
  std::vector<std::thread> runs;
  for (auto& texts : seen)
    runs.emplace_back([&f, &texts] { texts = CacheFixture::texts(f.export_once()); });
  for (auto& run : runs) run.join();
  for (const auto& texts : seen) CHECK(texts == f.fresh);
  CHECK(!f.warnings.empty());
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(f.cache))
    names.push_back(entry.path().filename().string());
  CHECK(names == std::vector<std::string>{gr.parent_path().filename().string()});
  f.warnings.clear();
  CHECK(f.export_once().reused);
}

TEST_CASE("cache clear removes the cache's own entries and nothing else") {
  CacheFixture f;
  const auto cache = f.cache;
  // Someone else's: a directory with an export.txt of its own, a .tmp- directory that is not a
  // temporary's name, a symlink to a directory outside, a plain file.
  fs::create_directories(cache / "0123456789abcdef-0123456789abcdef");
  write_text(cache / "0123456789abcdef-0123456789abcdef" / "export.txt", "my notes\n");
  fs::create_directories(cache / ".tmp-x");
  write_text(cache / ".tmp-x" / "keep", "mine\n");
  const auto outside = f.dir / "outside";
  fs::create_directories(outside);
  write_text(outside / "export.txt", "mosb export cache 2\n");
  fs::create_directory_symlink(outside, cache / "fedcba9876543210-fedcba9876543210");
  write_text(cache / "notes.txt", "mine\n");
  // A temporary left by a killed run (no process has PID 2^22 + 1 under the default pid_max).
  fs::create_directories(cache / ".tmp-4194305-00112233aabbccdd");
  const auto cleared = clear_export_cache(cache);
  CHECK(cleared.removed == 2);
  CHECK(cleared.left.size() == 4);
  for (const auto& line : cleared.left) {
    CHECK(line.find("left alone") != std::string::npos);
    CHECK(line.find('\n') == std::string::npos);
  }
  CHECK(slurp(cache / "0123456789abcdef-0123456789abcdef" / "export.txt") == "my notes\n");
  CHECK(slurp(cache / ".tmp-x" / "keep") == "mine\n");
  CHECK(fs::is_symlink(cache / "fedcba9876543210-fedcba9876543210"));
  CHECK(slurp(outside / "export.txt") == "mosb export cache 2\n");
  CHECK(slurp(cache / "notes.txt") == "mine\n");
  CHECK(!fs::exists(cache / ".tmp-4194305-00112233aabbccdd"));
  CHECK(fs::exists(cache / "0123456789abcdef-0123456789abcdef"));
}

// BENCHMARKS.md, "Export cache verified (issue 43 §3)": the check a reused export costs (reading
// and hashing every file) against making the export. Skipped unless asked for by name.
TEST_CASE("export cache: the check against the export, timed" * doctest::skip()) {
  TempDir dir;
  const auto median_seconds = [](int runs, const auto& once) {
    std::vector<double> seconds;
    for (int k = 0; k < runs; ++k) {
      const auto start = std::chrono::steady_clock::now();
      once();
      seconds.push_back(
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(seconds.begin(), seconds.end());
    return seconds[seconds.size() / 2];
  };
  const std::pair<const char*, GraphInput> instances[] = {
      {"NetMaker 10k", generate_netmaker({})}, {"Grid 300x300", generate_grid({300, 300, 2, 1})}};
  for (const auto& [name, input] : instances) {
    const auto instance = dir / "i.mosb";
    const auto cache = dir / "cache";
    write_graph(input, instance);
    const auto digest = GraphReader::open(instance).digest();
    const DimacsExportOptions options;
    const auto exported = median_seconds(7, [&] {
      clear_export_cache(cache);
      CHECK(!cached_export(cache, instance, digest, options).reused);
    });
    std::uint64_t bytes = 0;
    for (const auto& path : cached_export(cache, instance, digest, options).files.written)
      bytes += fs::file_size(path);
    const auto checked =
        median_seconds(21, [&] { CHECK(cached_export(cache, instance, digest, options).reused); });
    std::printf("%s: %.1f MB of text; export %.1f ms, check of a reused export %.2f ms (%.1f%%)\n",
                name, static_cast<double>(bytes) / 1e6, exported * 1e3, checked * 1e3,
                100 * checked / exported);
    clear_export_cache(cache);
  }
}
