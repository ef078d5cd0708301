// `mosb solutions merge A.sol B.sol ... -o all.sol`: the parts of one run (the shards of `mosb run
// --shard i/N`, the files of `mosb run --slurm DIR`) joined into one solution file (spec/RUN.md
// §7). The checks and the file are mosb::SolutionMerge; this parses, prints and picks the exit
// code.
#include <CLI/CLI.hpp>
#include <iostream>
#include <map>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/solution_merge.hpp"

namespace mosb::cli {
namespace {

constexpr int kConflict = 2;  // the inputs do not belong together, as a usage error
constexpr std::size_t kListed = 20;

struct MergeArgs {
  std::vector<std::string> inputs;
  std::string output;
  bool allow_missing = false, json = false;
};

// "2, 6, 10 and 7 more"
std::string query_list(const std::vector<std::uint64_t>& queries) {
  std::string text;
  for (std::size_t k = 0; k < queries.size() && k < kListed; ++k)
    text += (k ? ", " : "") + std::to_string(queries[k]);
  if (queries.size() > kListed)
    text += " and " + std::to_string(queries.size() - kListed) + " more";
  return text;
}

void print_json(const MergeArgs& a, const SolutionMerge& m, bool written) {
  JsonWriter j(std::cout);
  j.begin_object();
  j.key("output").value(a.output);
  j.key("written").value(written);
  j.key("query_set").value(m.query_set());
  j.key("queries").value(m.query_count());
  j.key("shards");
  if (m.shard_count())
    j.value(*m.shard_count());
  else
    j.null();
  j.key("inputs").begin_array();
  for (const auto& input : m.inputs()) {
    j.begin_object().key("file").value(input.file.string()).key("shard");
    if (input.shard)
      j.value(*input.shard);
    else
      j.null();
    j.key("queries").value(input.queries).end_object();
  }
  j.end_array();
  j.key("absent_shards").begin_array();
  for (const auto shard : m.absent_shards()) j.value(shard);
  j.end_array();
  j.key("missing").begin_array();
  for (const auto q : m.missing()) j.value(q);
  j.end_array();
  j.key("statuses");
  json_status_counts(j, m.status_counts());
  j.end_object();
}

// The missing queries, by shard when the inputs are shards.
void print_missing(const SolutionMerge& m) {
  const auto& missing = m.missing();
  std::cout << "missing: " << missing.size() << " of " << m.query_count()
            << " queries are not-run in every input\n";
  if (!m.shard_count()) {
    std::cout << "  queries " << query_list(missing) << "\n";
    return;
  }
  const auto n = *m.shard_count();
  std::map<std::uint64_t, std::vector<std::uint64_t>> by_shard;
  for (const auto q : missing) by_shard[q % n + 1].push_back(q);
  const auto absent = m.absent_shards();
  for (const auto& [shard, queries] : by_shard) {
    const bool no_file = std::find(absent.begin(), absent.end(), shard) != absent.end();
    std::cout << "  shard " << shard << "/" << n << (no_file ? " (no input)" : "") << ": "
              << queries.size() << (queries.size() == 1 ? " query: " : " queries: ")
              << query_list(queries) << "\n";
  }
}

int run_merge(const MergeArgs& a) {
  std::vector<std::filesystem::path> inputs(a.inputs.begin(), a.inputs.end());
  std::optional<SolutionMerge> merge;
  try {
    merge.emplace(inputs);
  } catch (const SolutionMergeConflict& e) {
    std::cerr << "mosb: " << escape_for_terminal(e.what()) << "\n";
    return kConflict;
  }
  const auto& m = *merge;
  const bool complete = m.missing().empty();
  const bool write = complete || a.allow_missing;
  if (write) m.write(a.output);
  if (a.json) {
    print_json(a, m, write);
    return write ? 0 : 1;
  }
  if (!complete) print_missing(m);
  if (!write) {
    std::cerr << "mosb: " << escape_for_terminal(a.output) << " not written: " << m.missing().size()
              << " queries are missing; run them (mosb run --slurm DIR --resume) or merge with "
                 "--allow-missing\n";
    return 1;
  }
  const auto counts = m.status_counts();
  std::cout << "wrote " << escape_for_terminal(a.output) << ": " << m.query_count()
            << " queries from " << m.inputs().size()
            << " files: " << status_counts_text(counts, false) << "\n";
  return 0;
}

}  // namespace

Command add_solutions_merge(CLI::App* solutions) {
  auto args = std::make_shared<MergeArgs>();
  auto* sub = solutions->add_subcommand(
      "merge",
      "Join the parts of one run (the shards of mosb run --shard or --slurm) into one solution "
      "file; exit 1 when queries are missing, 2 when the parts do not belong together");
  sub->add_option("SOLUTIONS", args->inputs,
                  "solution files of the same instance, objectives, query set, solver and limits, "
                  "each query run in at most one")
      ->required()
      ->check(CLI::ExistingFile);
  add_output_option(sub, args->output, "the merged solution file")->required();
  sub->add_flag("--allow-missing", args->allow_missing,
                "write the file even when some queries ran in no input (they stay not-run)");
  add_json_flag(sub, args->json);
  return {sub, [args] { return run_merge(*args); }};
}

}  // namespace mosb::cli
