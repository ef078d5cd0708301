// `mosb suite build DIR [--raw RAWDIR]`: every benchmark of the paper that can be generated here,
// every raw-source benchmark whose inputs RAWDIR holds, and their MANIFEST. `mosb suite release
// RESULTS --references REFS -o STORE`: an experiment's instances and references as a published
// store (mosb::pages::release_suite).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/converters/raw_suite.hpp"
#include "mosb/converters/suite.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/report/release.hpp"
#include "mosb/store.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct SuiteBuildArgs {
  std::string directory;
  std::string raw;
  std::vector<std::string> benchmarks;
  unsigned threads = 0;
  bool no_pack = false;
  bool no_generated = false;
  bool replace = false;
  bool json = false;
};

int run_suite_build(const SuiteBuildArgs& a) {
  if (a.no_generated && a.raw.empty()) throw UsageError("--no-generated needs --raw RAWDIR");
  std::vector<converters::SuiteInstance> instances;
  if (!a.no_generated) instances = converters::published_generated_suite();
  std::vector<converters::RawStatus> raw;
  if (!a.raw.empty()) {
    auto plan = converters::plan_raw_suite(a.raw);
    for (auto& instance : plan.instances) instances.push_back(std::move(instance));
    raw = std::move(plan.statuses);
  }
  std::vector<std::pair<std::string, std::string>> unbuilt;
  for (const auto& s : raw)
    if (!s.missing.empty()) unbuilt.emplace_back(s.name, converters::raw_status_text(s));
  try {
    instances = converters::select_suite_instances(std::move(instances), a.benchmarks, unbuilt);
  } catch (const Error& e) {
    if (e.code() != ErrorCode::invalid_argument) throw;
    throw UsageError(error_text(e));
  }
  // Raw recipes left out by --benchmark are not reported as built.
  std::erase_if(raw, [&](const converters::RawStatus& s) {
    return !a.benchmarks.empty() && s.missing.empty() &&
           std::none_of(instances.begin(), instances.end(),
                        [&](const converters::SuiteInstance& i) { return i.name == s.name; });
  });
  TerminalProgress progress;
  const auto entries = converters::run_suite(
      a.directory, instances, {a.threads, progress.callback(), suite_pack(!a.no_pack), a.replace});
  if (!a.json)
    for (const auto& s : raw) std::cout << converters::raw_status_text(s) << '\n';
  return report_suite(a.directory, "suite", entries, a.json, [&](JsonWriter& out) {
    if (a.raw.empty()) return;
    out.key("raw").begin_array();
    for (const auto& s : raw) {
      out.begin_object();
      out.key("name").value(s.name);
      out.key("status").value(s.missing.empty() ? "built" : "skipped");
      out.key("missing").begin_array();
      for (const auto& m : s.missing) out.value(m);
      out.end_array();
      out.key("source").value(s.source);
      out.end_object();
    }
    out.end_array();
  });
}

struct SuiteReleaseArgs {
  std::string results, references, output;
  bool pack_references = false;
};

int run_suite_release(const SuiteReleaseArgs& a) {
  TerminalProgress progress;
  pages::ReleaseOptions options;
  options.pack = *suite_pack(true);
  options.pack_references = a.pack_references;
  options.progress = progress.callback();
  const auto release = pages::release_suite(a.results, a.references, a.output, options);
  std::size_t references = 0;
  for (const auto& e : release.entries) references += e.solutions ? 1 : 0;
  std::cout << "wrote " << escape_for_terminal(a.output) << ": "
            << release.entries.size() - references << " instances, " << references
            << " references, MANIFEST, " << kStoreSummary << ", " << kStoreReadme << '\n';
  for (const auto& file : release.without_reference)
    std::cerr << "mosb: note: " << escape_for_terminal(file) << " has no reference\n";
  return 0;
}

}  // namespace

Command add_suite(CLI::App& app) {
  auto* suite = app.add_subcommand("suite", "The paper's published benchmark suite");
  auto* build = suite->add_subcommand("build",
                                      "Write the 49 Grid and 12 NetMaker instances, and with --raw "
                                      "every raw-source benchmark whose "
                                      "inputs RAWDIR holds, packed, and their MANIFEST into DIR");
  build->footer(
      "Raw-source benchmarks (--raw RAWDIR; inputs by their download names, .gz or plain; "
      "spec/MANIFEST.md, \"Raw-source benchmarks\"):\n"
      "  DIMACS-NY      USA-road-d.NY.gr.gz USA-road-t.NY.gr.gz USA-road-d.NY.co.gz\n"
      "                 [NY.elev: DIMACS-Extended-NY_3/_4/_5] [USA-road-NY-queries: set default]\n"
      "  DIMACS-FLA     USA-road-d.FLA.gr.gz USA-road-t.FLA.gr.gz USA-road-d.FLA.co.gz\n"
      "  GER_10         GER_10.txt (FMI, 10 cost columns)\n"
      "  Games-GUARDS-M M.map M.guards (random512-20-1, and every M.guards in RAWDIR)\n"
      "  Panda-RRG_2    Panda-RRG_2.graphml (aggregate clearance)\n"
      "  Panda-RRG_8    Panda-RRG_8.graphml (per-link clearance)\n"
      "Each is byte-identical to its `mosb convert ...` command; a recipe without its inputs is "
      "reported as skipped.");
  auto args = std::make_shared<SuiteBuildArgs>();
  build->add_option("DIR", args->directory, "the suite directory (created if needed)")->required();
  build->add_option("--raw", args->raw,
                    "also build every raw-source benchmark whose input files are in RAWDIR");
  build->add_option("--benchmark", args->benchmarks,
                    "build only the benchmarks whose name matches this shell pattern, e.g. "
                    "'Grid-300x*' (repeatable; default: all)");
  build->add_option("--threads", args->threads, "worker threads (default: all cores)")
      ->check(unsigned_integer(std::numeric_limits<unsigned>::max()))
      ->group("");
  // For tests: the raw part alone, without the minutes the generated instances take.
  build->add_flag("--no-generated", args->no_generated, "skip the Grid and NetMaker instances")
      ->group("");
  build->add_flag("--no-pack", args->no_pack,
                  "write the files unpacked (mosb pack makes the same packed files from them)");
  build->add_flag("--replace", args->replace,
                  "list only the instances this build writes (default: add them to DIR's "
                  "MANIFEST, keeping, after checking them, the entries it lists and this build "
                  "does not rebuild)");
  add_json_flag(build, args->json);
  auto* release = suite->add_subcommand(
      "release",
      "Write an experiment's instances (packed) and exact references into a new store to publish, "
      "with SUMMARY.csv (the suite table) and README.md (the protocol)");
  auto release_args = std::make_shared<SuiteReleaseArgs>();
  release->add_option("RESULTS", release_args->results, "the experiment's results directory")
      ->required()
      ->check(CLI::ExistingDirectory);
  release
      ->add_option("--references", release_args->references,
                   "the references (mosb solutions reference -o REFS), a directory or a file")
      ->required()
      ->check(CLI::ExistingPath);
  release->add_option("-o,--output", release_args->output, "the new store (absent or empty)")
      ->required();
  release->add_flag("--pack-references", release_args->pack_references,
                    "pack the references too (format 1.6): a smaller download, which a pull "
                    "then decodes to check");
  return group(suite, {{build, [args] { return run_suite_build(*args); }},
                       {release, [release_args] { return run_suite_release(*release_args); }}});
}

}  // namespace mosb::cli
