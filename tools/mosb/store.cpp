// `mosb store init|add|list|verify|instance|pull DIR`: the CLI of mosb::Store
// (lib/store/include/mosb/store.hpp) and of mosb::pull (lib/pull/include/mosb/pull.hpp).
#include "mosb/store.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <iostream>
#include <map>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/parallel.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pull.hpp"
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
  // pull
  std::string url;
  std::vector<std::string> benchmarks;
  std::vector<std::string> views;
  std::vector<std::string> globs;
  unsigned jobs = PullOptions{}.jobs;
  bool unpack = false;
  bool no_references = false;
  bool dry_run = false;
  unsigned stall_timeout = PullOptions{}.stall_timeout_seconds;
  std::uint64_t check_memory = StreamingVerifyOptions{}.memory;
  std::optional<std::uint64_t> check_disk;
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
  json.key("kind").value(e.solutions ? "solutions" : "instance");
  if (const auto& s = e.solutions) {
    json.key("instance").value(s->instance);
    json.key("epsilon").value(s->epsilon);
    json.key("solver").value(s->solver);
    json.key("solvers").begin_array();
    for (const auto& name : s->solvers) json.value(name);
    json.end_array();
    json.key("statuses").begin_object();
    for (const auto& [status, count] : s->statuses) json.key(status).value(count);
    json.end_object();
    json.key("vectors").value(s->vectors);
    json.key("statistics").begin_array();
    for (const auto& name : s->statistics) json.value(name);
    json.end_array();
  }
  json.end_object();
}

// Names read from a MANIFEST or a file, as a terminal shows them: escaped, "-" when empty.
std::string shown(const std::string& name) {
  return name.empty() ? "-" : escape_for_terminal(name);
}

std::string listed_or_dash(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ",") + escape_for_terminal(n);
  return out.empty() ? "-" : out;
}

int run_init(const StoreArgs& a) {
  Store::init(a.directory);
  std::cout << "created an empty store in " << escape_for_terminal(a.directory) << '\n';
  return 0;
}

int run_remove(const StoreArgs& a) {
  auto store = Store::open(a.directory);
  const auto removed = store.remove(a.files);
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("store").value(a.directory);
    json.key("removed").begin_array();
    for (const auto& e : removed) write_entry(json, e);
    json.end_array();
    json.end_object();
  } else {
    for (const auto& e : removed)
      std::cout << "removed " << escape_for_terminal(e.file) << " (digest " << e.digest << ")\n";
  }
  return 0;
}

int run_add(const StoreArgs& a) {
  auto store = Store::open(a.directory);
  TerminalProgress progress;
  std::vector<std::filesystem::path> files(a.files.begin(), a.files.end());
  Store::AddOptions options;
  options.move = a.move;
  options.check_memory = a.check_memory;
  options.check_disk = a.check_disk;
  options.progress = progress.callback();
  if (a.pack) options.pack = PackOptions{a.level, thread_count(0)};
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
      std::cout << (a.move ? "moved " : "added ") << escape_for_terminal(e.file)
                << (e.packed ? " packed" : "") << " (digest " << e.digest << ")\n";
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
  for (const auto& e : store.manifest().entries) {
    std::cout << escape_for_terminal(e.file) << "  " << e.size << " bytes  "
              << (e.packed ? "packed  " : "") << "benchmark " << shown(e.benchmark) << "  views "
              << listed_or_dash(e.views) << "  queries " << listed_or_dash(e.query_sets)
              << "  digest " << e.digest;
    if (const auto& s = e.solutions) {
      std::string statuses;
      for (const auto& [status, count] : s->statuses)
        statuses += (statuses.empty() ? "" : ", ") + std::to_string(count) + " " + status;
      std::cout << "  fronts of " << s->instance << " by " << listed_or_dash(s->solvers)
                << (s->epsilon == "0" ? ", exact" : ", epsilon " + escape_for_terminal(s->epsilon))
                << ": " << (statuses.empty() ? "no query" : statuses);
    }
    std::cout << '\n';
  }
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
    std::cout << escape_for_terminal(found.path.string()) << '\n'
              << "view " << (view.empty() ? "- (every objective)" : escape_for_terminal(view))
              << "  queries " << shown(found.query_set) << "  digest " << found.reader.digest()
              << '\n';
  }
  return 0;
}

// Fetches what the store lacks; one line per entry on stdout (`fetched`, `present`, or with
// --dry-run `would fetch`), one line per refused entry on stderr, exit 1 when any was refused.
int run_pull(const StoreArgs& a) {
  PullOptions options;
  options.benchmarks = a.benchmarks;
  options.views = a.views;
  options.files = a.globs;
  options.jobs = a.jobs;
  options.unpack = a.unpack;
  options.references = !a.no_references;
  options.dry_run = a.dry_run;
  options.stall_timeout_seconds = a.stall_timeout;
  options.check_memory = a.check_memory;
  options.check_disk = a.check_disk;
  const auto result = [&] {
    TerminalProgress progress;  // its line ends before the report is printed
    options.progress = progress.bytes_callback();
    std::map<PullStatus, std::size_t> counts;
    if (options.progress)
      options.settled = [&](const PulledEntry& entry, std::size_t settled, std::size_t selected) {
        ++counts[entry.status];
        progress.set_suffix("; entries " + std::to_string(settled) + "/" +
                            std::to_string(selected) + " (" +
                            std::to_string(counts[PullStatus::fetched]) + " fetched, " +
                            std::to_string(counts[PullStatus::present]) + " present, " +
                            std::to_string(counts[PullStatus::refused]) + " refused)");
      };
    return pull(a.directory, a.url, options);
  }();
  std::uint64_t planned_bytes = 0;
  std::map<PullStatus, std::size_t> counts;
  for (const auto& p : result.entries) {
    ++counts[p.status];
    if (p.status == PullStatus::planned) planned_bytes += p.entry.size;
  }
  for (const auto& p : result.entries)
    if (p.status == PullStatus::refused)
      std::cerr << "mosb: refused " << escape_for_terminal(p.entry.file) << ": "
                << escape_for_terminal(error_text(p.reason)) << '\n';
  if (a.json) {
    JsonWriter json(std::cout);
    json.begin_object();
    json.key("store").value(a.directory);
    json.key("manifest").value(result.manifest_url);
    json.key("dry_run").value(a.dry_run);
    json.key("ok").value(result.ok());
    for (const auto status : {PullStatus::fetched, PullStatus::present, PullStatus::planned}) {
      if ((a.dry_run && status == PullStatus::fetched) ||
          (!a.dry_run && status == PullStatus::planned))
        continue;
      json.key(status == PullStatus::planned ? "would_fetch"
                                             : std::string(kPullStatusNames.name(status)))
          .begin_array();
      for (const auto& p : result.entries) {
        if (p.status != status) continue;
        json.begin_object();
        json.key("file").value(p.entry.file);
        json.key("size").value(p.entry.size);
        if (status == PullStatus::fetched) {
          json.key("received").value(p.received);
          json.key("resumed_from").value(p.resumed_from);
          json.key("restarted").value(p.restarted);
        }
        json.end_object();
      }
      json.end_array();
    }
    json.key("refused").begin_array();
    for (const auto& p : result.entries) {
      if (p.status != PullStatus::refused) continue;
      json.begin_object();
      json.key("file").value(p.entry.file);
      json.key("reason").value(error_text(p.reason));
      json.end_object();
    }
    json.end_array();
    json.key("bytes").value(result.bytes);
    json.key("seconds").value(result.seconds);
    json.end_object();
  } else {
    for (const auto& p : result.entries) {
      const auto file = escape_for_terminal(p.entry.file);
      if (p.status == PullStatus::fetched)
        std::cout << "fetched " << file << " (" << p.entry.size << " bytes"
                  << (p.resumed_from ? ", resumed at byte " + std::to_string(p.resumed_from) : "")
                  << (p.restarted.empty() ? "" : "; " + escape_for_terminal(p.restarted)) << ")\n";
      else if (p.status == PullStatus::present)
        std::cout << "present " << file << '\n';
      else if (p.status == PullStatus::planned)
        std::cout << "would fetch " << file << " (" << p.entry.size << " bytes)\n";
    }
    if (a.dry_run)
      std::cout << counts[PullStatus::planned] << " to fetch (" << planned_bytes << " bytes), "
                << counts[PullStatus::present] << " present, " << counts[PullStatus::refused]
                << " refused\n";
    else
      std::cout << counts[PullStatus::fetched] << " fetched, " << counts[PullStatus::present]
                << " present, " << counts[PullStatus::refused] << " refused; " << result.bytes
                << " bytes received in " << result.seconds << " s\n";
  }
  return result.ok() ? 0 : 1;
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
  auto* store = app.add_subcommand(
      "store", "A directory of instances, their reference fronts and the MANIFEST listing them");
  auto args = std::make_shared<StoreArgs>();
  auto directory = [&](CLI::App* sub) {
    sub->add_option("DIR", args->directory, "the store directory")->required();
  };
  auto* init = store->add_subcommand("init", "Create an empty store (a MANIFEST) in DIR");
  directory(init);
  auto* add = store->add_subcommand(
      "add",
      "Copy (or move) .mosb files into the store: instances, and solution files (references) "
      "checked against their instance in the store or in the same add; the MANIFEST is "
      "rewritten last");
  directory(add);
  add->add_option("FILE", args->files, "the files to add (instances, solution files)")->required();
  add->add_flag("--move", args->move, "move the files instead of copying them");
  add_check_memory_option(add, args->check_memory);
  add_check_disk_option(add, args->check_disk);
  add->add_flag("--pack", args->pack,
                "store each unpacked file packed (as mosb pack does), instances and solution "
                "files alike");
  add->add_option("--level", args->level,
                  "zstd level for --pack (fixed, so the bytes are reproducible)")
      ->check(unsigned_integer(std::numeric_limits<int>::max()))
      ->check(CLI::Range(1, 22))
      ->capture_default_str()
      ->needs(add->get_option("--pack"));
  add_json_flag(add, args->json);
  auto* remove = store->add_subcommand(
      "remove",
      "Remove entries and their files from the store; an instance whose references stay is "
      "refused (remove them with it, or first)");
  directory(remove);
  remove->add_option("FILE", args->files, "the entries' file names, as the MANIFEST lists them")
      ->required();
  add_json_flag(remove, args->json);
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
  auto* pull_command = store->add_subcommand(
      "pull",
      "Fetch the store published at URL (http, https, file:// or a directory) into DIR: each "
      "entry checked (size, SHA-256, then as store add checks it) before it is placed and listed; "
      "interrupted transfers continue where they stopped");
  directory(pull_command);
  pull_command->add_option("URL", args->url, "where the store is published (URL/MANIFEST)")
      ->required();
  pull_command->add_option("--benchmark", args->benchmarks,
                           "only entries of this benchmark (a glob; repeatable)");
  pull_command->add_option("--view", args->views,
                           "only entries serving this view (a glob; repeatable)");
  pull_command->add_option("--file", args->globs,
                           "only entries of this file name (a glob; repeatable)");
  pull_command->add_option("--jobs", args->jobs, "transfers at once")
      ->check(unsigned_integer(256))
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  pull_command->add_flag("--no-references", args->no_references,
                         "instances alone: leave the published solution files (references)");
  pull_command->add_flag("--unpack", args->unpack,
                         "unpack packed entries into DIR/.cache once they are listed");
  pull_command->add_flag("--dry-run", args->dry_run,
                         "say what would be fetched and what is present; write nothing");
  pull_command
      ->add_option("--stall-timeout", args->stall_timeout,
                   "seconds without a byte before a transfer is retried")
      ->check(unsigned_integer(86400))
      ->check(CLI::Range(1, 86400))
      ->capture_default_str();
  add_check_memory_option(pull_command, args->check_memory);
  add_check_disk_option(pull_command, args->check_disk);
  add_json_flag(pull_command, args->json);
  return group(store, {{init, [args] { return run_init(*args); }},
                       {pull_command, [args] { return run_pull(*args); }},
                       {instance, [args] { return run_instance(*args); }},
                       {add, [args] { return run_add(*args); }},
                       {remove, [args] { return run_remove(*args); }},
                       {list, [args] { return run_list(*args); }},
                       {verify, [args] { return run_store_verify(*args); }}});
}

}  // namespace mosb::cli
