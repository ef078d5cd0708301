#include <CLI/CLI.hpp>
#include <memory>

#include "graph_output.hpp"
#include "mosb/converters/netmaker_generator.hpp"
#include "mosb/converters/suite.hpp"

namespace mosb::cli {

namespace {

struct NetMakerArgs {
  converters::NetMakerParameters params;
  std::string name;
  GraphOutput output;
  std::string suite;
  unsigned threads = 0;
  bool pack = false;
};

int run_netmaker(NetMakerArgs a, const CLI::App& app) {
  if (!a.suite.empty()) {
    TerminalProgress progress;
    // The suite's N list, unless --vertices narrows it (tests use a small N).
    const auto counts = app.count("--vertices") ? std::vector<std::uint32_t>{a.params.vertices}
                                                : converters::paper_netmaker_vertex_counts();
    const auto entries =
        converters::run_suite(a.suite, converters::netmaker_suite(a.params.seed, counts),
                              {a.threads, progress.callback(), suite_pack(a.pack)});
    return report_suite(a.suite, "NetMaker", entries, a.output.json);
  }
  if (a.output.file.empty()) throw UsageError("--output FILE is required (or --suite DIR)");
  if (!a.name.empty()) a.params.name = a.name;
  return write_converted(a.output, {},
                         [&](const Progress&) { return converters::netmaker_graph(a.params); });
}

}  // namespace

Command add_generate_netmaker(CLI::App& generate) {
  auto* netmaker = generate.add_subcommand(
      "netmaker",
      "The paper's NetMaker graph: a random Hamiltonian cycle plus locality arcs (3 objectives)");
  auto args = std::make_shared<NetMakerArgs>();
  auto& p = args->params;
  netmaker->add_option("--vertices", p.vertices, "N, the number of vertices")
      ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
      ->check(CLI::Range(2u, 100000000u))
      ->capture_default_str();
  auto* amin =
      netmaker->add_option("--amin", p.amin, "out-degrees are drawn from {amin+1, ..., amax}")
          ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
          ->capture_default_str();
  auto* amax = netmaker->add_option("--amax", p.amax, "the largest out-degree, cycle arc included")
                   ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
                   ->check(CLI::Range(1u, 100000u))
                   ->capture_default_str();
  auto* locality = netmaker
                       ->add_option("--locality", p.locality,
                                    "I: locality arcs join u to ids within u +- floor(I/2)")
                       ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
                       ->capture_default_str();
  add_seed_option(netmaker, p.seed, "seed of the specified generator (with --suite: of the suite)");
  auto* queries =
      netmaker->add_option("--queries", p.queries, "number of distinct start-goal pairs")
          ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
          ->check(CLI::Range(1u, 1000000u))
          ->capture_default_str();
  auto* percent = netmaker
                      ->add_option("--query-percent", p.query_percent,
                                   "starts among the first, goals among the last P% of vertex ids")
                      ->check(unsigned_integer(std::numeric_limits<std::uint32_t>::max()))
                      ->check(CLI::Range(1u, 50u))
                      ->capture_default_str();
  auto* name =
      netmaker->add_option("--name", args->name, "benchmark name (default NetMaker-N<N>-I<I>)");
  add_graph_output_options(netmaker, args->output);
  auto* suite = netmaker->add_option(
      "--suite", args->suite,
      "write the paper's 12 NetMaker graphs and a MANIFEST into this directory");
  netmaker
      ->add_option("--threads", args->threads, "worker threads for --suite (default: all cores)")
      ->check(unsigned_integer(std::numeric_limits<unsigned>::max()))
      ->group("");
  for (auto* single_only :
       {amin, amax, locality, queries, percent, name, netmaker->get_option("--output"),
        netmaker->get_option("--expect-digest"), netmaker->get_option("--view")})
    suite->excludes(single_only);
  add_suite_pack_flag(netmaker, args->pack)->needs(suite);
  return {netmaker, [args, netmaker] { return run_netmaker(*args, *netmaker); }};
}

}  // namespace mosb::cli
