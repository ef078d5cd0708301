// `mosb store init|add|list|verify DIR`: the CLI of mosb::Store (lib/store/include/mosb/store.hpp).
#include "mosb/store.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <memory>
#include <thread>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/utf8.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct StoreArgs {
  std::string directory;
  std::vector<std::string> files;
  std::string name;
  bool move = false;
  bool pack = false;
  int level = PackOptions{}.level;
  unsigned threads = 0;
  bool json = false;
};

void write_entry(JsonWriter& json, const ManifestEntry& e) {
  json.begin_object();
  json.key("file").value(e.file);
  json.key("size").value(e.size);
  json.key("sha256").value(e.sha256);
  json.key("digest").value(e.digest);
  json.key("format_version").value(e.format_version);
  json.key("packed").value(e.packed);
  json.key("benchmark").value(e.benchmark);
  json.key("views").begin_array();
  for (const auto& v : e.views) json.value(v);
  json.end_array();
  json.key("query_sets").begin_array();
  for (const auto& q : e.query_sets) json.value(q);
  json.end_array();
  json.key("sources").begin_array();
  for (const auto& s : e.sources) {
    json.begin_object();
    json.key("name").value(s.name);
    json.key("size").value(s.size);
    json.key("xxh3").value(s.xxh3);
    json.end_object();
  }
  json.end_array();
  json.end_object();
}

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ",") + n;
  return out.empty() ? "-" : out;
}

int run_init(const StoreArgs& a) {
  Store::init(a.directory);
  std::cout << "created an empty store in " << a.directory << '\n';
  return 0;
}

int run_add(const StoreArgs& a) {
  auto store = Store::open(a.directory);
  TerminalProgress progress;
  std::vector<std::filesystem::path> files(a.files.begin(), a.files.end());
  Store::AddOptions options{a.move, std::nullopt, progress.callback()};
  if (a.pack)
    options.pack = PackOptions{a.level, std::max(1U, std::thread::hardware_concurrency())};
  const auto added = store.add(files, options);
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("store").value(a.directory);
    json.key("added").begin_array();
    for (const auto& e : added) write_entry(json, e);
    json.end_array();
    json.end_object();
  } else {
    for (const auto& e : added)
      std::cout << (a.move ? "moved " : "added ") << e.file << (e.packed ? " packed" : "")
                << " (digest " << e.digest << ")\n";
  }
  return 0;
}

int run_list(const StoreArgs& a) {
  const auto store = Store::open(a.directory);
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("store").value(a.directory);
    json.key("entries").begin_array();
    for (const auto& e : store.manifest().entries) write_entry(json, e);
    json.end_array();
    json.end_object();
    return 0;
  }
  for (const auto& e : store.manifest().entries)
    std::cout << e.file << "  " << e.size << " bytes  " << (e.packed ? "packed  " : "")
              << "benchmark " << (e.benchmark.empty() ? "-" : e.benchmark) << "  views "
              << joined(e.views) << "  queries " << joined(e.query_sets) << "  digest " << e.digest
              << '\n';
  std::cout << store.manifest().entries.size() << " entries"
            << (store.manifest().legacy ? " (older TSV MANIFEST: no SHA-256 listed)" : "") << '\n';
  return 0;
}

int run_store_verify(const StoreArgs& a) {
  const auto store = Store::open(a.directory);
  TerminalProgress progress;
  const auto checks = store.verify({a.threads, progress.callback()});
  return report_checks(checks, a.json);
}

// Resolves a name as solvers do (Store::instance) and says which file, view and query set serve
// it; for a packed entry the unpacked copy is made in the store's cache, and without one (a
// read-only store) the answer is an error, not the packed file.
int run_instance(const StoreArgs& a) {
  const auto store = Store::open(a.directory);
  const auto found = store.instance(a.name);
  // A solver maps the path printed: a packed file decoded in memory (the store cannot be written)
  // has no path to give.
  if (found.entry.packed && found.path != store.directory() / kCacheDirectory / found.entry.file)
    throw Error(ErrorCode::io, (store.directory() / kCacheDirectory / found.entry.file).string() +
                                   ": cannot unpack there (the store cannot be written, or "
                                   "something else is in the way); "
                                   "mosb unpack " +
                                   (store.directory() / found.entry.file).string() +
                                   " -o FILE unpacks it elsewhere");
  const std::string view = found.view ? found.view->name : "";
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("name").value(a.name);
    json.key("path").value(found.path.string());
    json.key("file").value(found.entry.file);
    json.key("benchmark").value(found.entry.benchmark);
    json.key("view").value(view);
    json.key("query_set").value(found.query_set);
    json.key("digest").value(found.reader.digest());
    json.end_object();
  } else {
    std::cout << found.path.string() << '\n'
              << "view " << (view.empty() ? "- (every objective)" : view) << "  queries "
              << (found.query_set.empty() ? "-" : found.query_set) << "  digest "
              << found.reader.digest() << '\n';
  }
  return 0;
}

}  // namespace

int report_checks(const std::vector<FileCheck>& checks, bool json) {
  std::size_t failures = 0;
  for (const auto& c : checks) failures += c.ok() ? 0 : 1;
  if (json) {
    JsonWriter out(std::cout);
    out.begin_object();
    out.key("ok").value(failures == 0);
    out.key("files").begin_array();
    for (const auto& c : checks) {
      out.begin_object();
      out.key("file").value(c.file);
      out.key("ok").value(c.ok());
      if (!c.note.empty()) out.key("note").value(c.note);
      out.key("problems").begin_array();
      for (const auto& p : c.problems) {
        out.begin_object();
        out.key("kind").value(p.kind);
        out.key("detail").value(p.detail);
        out.end_object();
      }
      out.end_array();
      out.end_object();
    }
    out.end_array();
    out.end_object();
  } else {
    for (const auto& c : checks) {
      if (c.ok())
        std::cout << "OK   " << escape_for_terminal(c.file) << (c.note.empty() ? "" : ": " + c.note)
                  << '\n';
      for (const auto& p : c.problems)
        std::cout << "FAIL " << p.kind << ": " << escape_for_terminal(p.detail) << '\n';
    }
    std::cout << checks.size() << (checks.size() == 1 ? " file, " : " files, ") << failures
              << " with problems\n";
  }
  return failures == 0 ? 0 : 1;
}

Command add_store(CLI::App& app) {
  auto* store =
      app.add_subcommand("store", "A directory of instances and the MANIFEST listing them");
  auto args = std::make_shared<StoreArgs>();
  auto directory = [&](CLI::App* sub) {
    sub->add_option("DIR", args->directory, "the store directory")->required();
  };
  auto* init = store->add_subcommand("init", "Create an empty store (a MANIFEST) in DIR");
  directory(init);
  auto* add = store->add_subcommand(
      "add", "Copy (or move) .mosb files into the store; the MANIFEST is rewritten last");
  directory(add);
  add->add_option("FILE", args->files, "the .mosb files to add")->required();
  add->add_flag("--move", args->move, "move the files instead of copying them");
  add->add_flag("--pack", args->pack, "store each unpacked file packed (as mosb pack does)");
  add->add_option("--level", args->level,
                  "zstd level for --pack (fixed, so the bytes are reproducible)")
      ->check(unsigned_integer(std::numeric_limits<int>::max()))
      ->check(CLI::Range(1, 22))
      ->capture_default_str()
      ->needs(add->get_option("--pack"));
  add_json_flag(add, args->json);
  auto* list = store->add_subcommand("list", "Print the store's entries");
  directory(list);
  add_json_flag(list, args->json);
  auto* verify = store->add_subcommand(
      "verify", "Check every entry (size, SHA-256, digest, verify --level full) and extra files");
  directory(verify);
  verify->add_option("--threads", args->threads, "worker threads (default: all cores)")
      ->check(unsigned_integer(std::numeric_limits<unsigned>::max()))
      ->group("");
  add_json_flag(verify, args->json);
  auto* instance = store->add_subcommand(
      "instance",
      "Resolve BENCHMARK, VIEW or BENCHMARK/VIEW to the file a solver maps (a packed entry is "
      "unpacked into DIR/.cache first), verified in full");
  directory(instance);
  instance->add_option("NAME", args->name, "a benchmark, a view, or BENCHMARK/VIEW")->required();
  add_json_flag(instance, args->json);
  return group(store, {{init, [args] { return run_init(*args); }},
                       {instance, [args] { return run_instance(*args); }},
                       {add, [args] { return run_add(*args); }},
                       {list, [args] { return run_list(*args); }},
                       {verify, [args] { return run_store_verify(*args); }}});
}

}  // namespace mosb::cli
