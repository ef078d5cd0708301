// `mosb solutions reference RESULTS_OR_FILES --solvers A,B -o REFS/ [--prefer A]`: per instance
// view one reference file of the fronts the named exact solvers agree on (spec/EVALUATION.md §7).
// The cross-validation is mosb::cross_validate; a results directory lists its files
// (mosb::result_files).
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/experiment.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/solution_reference.hpp"
#include "mosb/solution_verify.hpp"

namespace mosb::cli {
namespace {

struct ReferenceArgs {
  std::vector<std::string> inputs;
  std::vector<std::string> solvers;
  std::string prefer, output;
  ComparisonOptions comparison;
  bool json = false;
};

std::string disagreement_line(const std::string& name, const ReferenceQuery& q) {
  std::string line = name + " query " + std::to_string(q.query) + ": " + q.first + " and " +
                     q.differing + " disagree";
  if (!q.first_difference.empty())
    line += ": " + cost_vector_text(q.first_difference) + " only in " +
            (q.difference_in_first ? q.first : q.differing);
  else
    line += " on the status";
  return line + (q.kind == ReferenceKind::preferred ? "; kept " + q.source + "'s (--prefer)"
                                                    : "; left out");
}

int run_reference(const ReferenceArgs& a) {
  std::vector<SolutionReader> files;
  for (const auto& input : a.inputs)
    for (const auto& path : experiment_result_files(input))
      files.push_back(SolutionReader::open_verified(path));
  ReferenceOptions options;
  options.solvers = a.solvers;
  if (!a.prefer.empty()) options.prefer = a.prefer;
  options.tolerance = a.comparison.tolerance;
  const auto groups = reference_groups(files, options);
  std::vector<std::vector<const SolutionReader*>> members(groups.size());
  std::vector<CrossValidation> validations;
  for (std::size_t g = 0; g < groups.size(); ++g) {  // every group checked before any write
    for (auto f : groups[g].files) members[g].push_back(&files[f]);
    validations.push_back(cross_validate(members[g], options));
  }
  check_reference_outputs(files, groups, a.output);
  std::error_code ec;
  std::filesystem::create_directories(a.output, ec);
  if (ec) throw Error(ErrorCode::io, a.output + ": cannot create: " + ec.message());
  for (std::size_t g = 0; g < groups.size(); ++g)
    write_reference(members[g], validations[g], options,
                    std::filesystem::path(a.output) / groups[g].name);
  if (a.json) {
    JsonWriter out(std::cout);
    out.begin_object().key("references").begin_array();
    for (std::size_t g = 0; g < groups.size(); ++g) {
      out.begin_object().key("file").value(
          (std::filesystem::path(a.output) / groups[g].name).string());
      for (const auto kind :
           {ReferenceKind::agreed, ReferenceKind::single, ReferenceKind::disagreement,
            ReferenceKind::preferred, ReferenceKind::unsolved})
        out.key(std::string(to_string(kind))).value(validations[g].count(kind));
      out.key("disagreements").begin_array();
      for (const auto& q : validations[g].queries) {
        if (q.kind != ReferenceKind::disagreement && q.kind != ReferenceKind::preferred) continue;
        out.begin_object().key("query").value(q.query);
        out.key("solvers").begin_array().value(q.first).value(q.differing).end_array();
        out.key("first_difference").begin_array();
        for (double v : q.first_difference) out.value(v);
        out.end_array().key("only_in").value(q.difference_in_first ? q.first : q.differing);
        out.key("kept").value(q.kind == ReferenceKind::preferred).end_object();
      }
      out.end_array().end_object();
    }
    out.end_array().end_object();
    std::cout << '\n';
    return 0;
  }
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const auto& v = validations[g];
    for (const auto& q : v.queries)
      if (q.kind == ReferenceKind::disagreement || q.kind == ReferenceKind::preferred)
        std::cout << escape_for_terminal(disagreement_line(groups[g].name, q)) << '\n';
    std::cout << "wrote "
              << escape_for_terminal((std::filesystem::path(a.output) / groups[g].name).string())
              << ": " << v.queries.size() << " queries, " << v.count(ReferenceKind::agreed)
              << " agreed, " << v.count(ReferenceKind::single) << " by one solver only, "
              << v.count(ReferenceKind::disagreement) << " disagreements left out, "
              << v.count(ReferenceKind::preferred) << " disagreements kept (--prefer), "
              << v.count(ReferenceKind::unsolved) << " unsolved\n";
  }
  return 0;
}

}  // namespace

Command add_solutions_reference(CLI::App* solutions) {
  auto args = std::make_shared<ReferenceArgs>();
  auto* sub = solutions->add_subcommand(
      "reference",
      "Per instance view, a reference file of the fronts the named exact solvers agree on");
  sub->add_option("RESULTS_OR_FILES", args->inputs,
                  "experiment results directories or solution files")
      ->required()
      ->check(CLI::ExistingPath);
  sub->add_option("--solvers", args->solvers, "the exact solvers cross-validated (A,B,...)")
      ->required()
      ->delimiter(',');
  sub->add_option("--prefer", args->prefer,
                  "where the solvers disagree, keep this one's front (default: leave it out)");
  sub->add_option("-o,--output", args->output, "the directory of the reference files")->required();
  add_comparison_options(sub, args->comparison);
  add_json_flag(sub, args->json);
  return {sub, [args] { return run_reference(*args); }};
}

}  // namespace mosb::cli
