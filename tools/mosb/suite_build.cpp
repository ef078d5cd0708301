// `mosb suite build DIR`: every benchmark of the paper that can be generated here, and its
// MANIFEST.
#include <CLI/CLI.hpp>
#include <memory>

#include "commands.hpp"
#include "mosb/converters/suite.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct SuiteBuildArgs {
  std::string directory;
  unsigned threads = 0;
  bool no_pack = false;
  bool json = false;
};

int run_suite_build(const SuiteBuildArgs& a) {
  // The published suite: seed 1, the paper's sizes; the same instances `generate grid|netmaker
  // --suite` writes, so a single file can still be rebuilt from its own command.
  constexpr std::uint64_t kSuiteSeed = 1;
  auto instances = converters::grid_suite(kSuiteSeed, converters::paper_grid_sizes());
  for (auto& instance :
       converters::netmaker_suite(kSuiteSeed, converters::paper_netmaker_vertex_counts()))
    instances.push_back(std::move(instance));
  TerminalProgress progress;
  const auto entries = converters::run_suite(
      a.directory, instances, {a.threads, progress.callback(), suite_pack(!a.no_pack)});
  return report_suite(a.directory, "suite", entries, a.json);
}

}  // namespace

Command add_suite(CLI::App& app) {
  auto* suite = app.add_subcommand("suite", "The paper's published benchmark suite");
  auto* build = suite->add_subcommand(
      "build", "Write the 49 Grid and 12 NetMaker instances, packed, and their MANIFEST into DIR");
  auto args = std::make_shared<SuiteBuildArgs>();
  build->add_option("DIR", args->directory, "the suite directory (created if needed)")->required();
  build->add_option("--threads", args->threads, "worker threads (default: all cores)")->group("");
  build->add_flag("--no-pack", args->no_pack,
                  "write the files unpacked (mosb pack makes the same packed files from them)");
  add_json_flag(build, args->json);
  return group(suite, {{build, [args] { return run_suite_build(*args); }}});
}

}  // namespace mosb::cli
