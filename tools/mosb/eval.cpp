// `mosb eval`: solvers' solution files against a reference solution file (spec/EVALUATION.md §4).
// The evaluation is mosb::compare_solvers, the tables mosb::tables; this file parses options and
// prints.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <span>
#include <sstream>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/experiment.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/pack.hpp"
#include "mosb/pull.hpp"
#include "mosb/report/report.hpp"
#include "mosb/report/tables.hpp"
#include "mosb/solution_verify.hpp"
#include "mosb/solver_comparison.hpp"

namespace mosb::cli {

namespace {

struct EvalArgs {
  std::string results;  // an experiment's results directory: the solver table mode
  std::string reference;
  std::vector<std::string> solutions;
  std::string epsilons = "0.01,0.05,0.1";
  ComparisonOptions options;
  bool json = false, csv = false, latex = false, per_query = false, common_queries = false;
};

// "covered", or "NOT covered (k uncovered[, m extra])".
std::string coverage_text(const EpsilonCoverage& c) {
  if (c.covered) return "covered";
  return "NOT covered (" + std::to_string(c.uncovered) + " uncovered" +
         (c.extra ? ", " + std::to_string(c.extra) + " extra" : std::string()) + ")";
}

void print_query_lines(const SolutionEvaluation& result, const std::vector<Ratio>& eps,
                       const std::vector<std::string>& eps_text) {
  for (const auto& q : result.queries) {
    std::cout << "query " << q.query << ": " << to_string(q.solution_status);
    if (!q.front) {
      if (q.reference_status != QueryStatus::solved)
        std::cout << " (reference " << to_string(q.reference_status) << ", not evaluated)";
      else
        std::cout << " (not solved: FAIL at every ε)";
      std::cout << (q.failed ? " FAIL" : "") << '\n';
      continue;
    }
    const auto& f = *q.front;
    std::cout << ", |S| " << f.solution_size << ", |R| " << f.reference_size << ", |S|/|R| "
              << (f.reference_size
                      ? static_cast<double>(f.solution_size) / static_cast<double>(f.reference_size)
                      : 0.0)
              << ", achieved ε " << achieved_epsilon_text(f, result.exact_arithmetic);
    for (std::size_t k = 0; k < eps.size(); ++k) {
      std::cout << ", ε=" << eps_text[k] << ' ' << coverage_text(f.coverage[k]);
    }
    if (!q.worst_reference_values.empty())
      std::cout << ", worst reference vector " << cost_vector_text(q.worst_reference_values);
    std::cout << (q.failed ? " FAIL" : "") << '\n';
    if (!f.dominated_by_reference.empty() && result.solver_claims_exact)
      std::cout << "query " << q.query << ": SOLVER BUG: " << f.dominated_by_reference.size()
                << " returned vector(s) strictly dominated by the reference (the solver claims "
                   "ε = 0)\n";
  }
}

void json_query(JsonWriter& j, const QueryEvaluation& q, bool exact,
                const std::vector<std::string>& eps_text) {
  j.begin_object()
      .key("query")
      .value(q.query)
      .key("status")
      .value(to_string(q.solution_status))
      .key("reference_status")
      .value(to_string(q.reference_status))
      .key("failed")
      .value(q.failed);
  if (q.front) {
    const auto& f = *q.front;
    j.key("solution_size").value(std::uint64_t{f.solution_size});
    j.key("reference_size").value(std::uint64_t{f.reference_size});
    j.key("achieved_epsilon").value(achieved_epsilon_text(f, exact));
    j.key("achieved_epsilon_value").value(f.achieved_value);
    j.key("coverage").begin_array();
    for (std::size_t k = 0; k < f.coverage.size(); ++k)
      j.begin_object()
          .key("epsilon")
          .value(eps_text[k])
          .key("covered")
          .value(f.coverage[k].covered)
          .key("uncovered")
          .value(f.coverage[k].uncovered)
          .key("extra")
          .value(f.coverage[k].extra)
          .key("outcome")
          .value(to_string(*q.outcome(k)))
          .end_object();
    j.end_array();
    j.key("worst_reference").begin_array();
    for (double v : q.worst_reference_values) j.value(v);
    j.end_array();
    j.key("dominated_by_reference").begin_array();
    for (auto i : f.dominated_by_reference) j.value(std::uint64_t{i});
    j.end_array();
  }
  j.end_object();
}

void print_json(const SolverComparison& result, const std::string& reference,
                std::uint64_t query_count, const std::vector<std::string>& eps_text) {
  JsonWriter j(std::cout);
  j.begin_object().key("ok").value(!result.failed);
  j.key("reference").value(reference).key("queries").value(query_count);
  j.key("epsilons").begin_array();
  for (const auto& e : eps_text) j.value(e);
  j.end_array();
  j.key("tolerance").value(result.tolerance);
  j.key("common_queries").value(std::uint64_t{result.common_queries.size()});
  j.key("runtime").value(to_string(result.runtime));
  j.key("runtime_shift_seconds").value(result.runtime_shift_seconds);
  j.key("solvers").begin_array();
  for (const auto& s : result.solvers) {
    j.begin_object().key("name").value(s.name).key("file").value(s.file);
    j.key("ok").value(!s.evaluation.failed).key("statuses");
    json_status_counts(j, s.own.statuses);
    j.key("front_size");
    json_distribution(j, s.own.front_size, true, false);
    j.key("not_solved").value(s.not_solved);
    j.key("solved_unreachable").value(s.solved_unreachable).key("epsilons").begin_array();
    for (std::size_t k = 0; k < eps_text.size(); ++k)
      j.begin_object()
          .key("epsilon")
          .value(eps_text[k])
          .key(to_string(QueryOutcome::covered))
          .value(s.per_epsilon[k].covered)
          .key(to_string(QueryOutcome::not_covered))
          .value(s.per_epsilon[k].not_covered)
          .key(to_string(QueryOutcome::dominated))
          .value(s.per_epsilon[k].dominated)
          .key(to_string(QueryOutcome::not_solved))
          .value(s.not_solved)
          .end_object();
    j.end_array();
    j.key("achieved_epsilon");
    json_distribution(j, s.achieved_epsilon, false, false);
    j.key("size_ratio");
    json_distribution(j, s.size_ratio, false, false);
    j.key("runtime_recorded").value(s.runtime_recorded).key("runtime_seconds");
    json_distribution(j, s.runtime, false, true);
    j.key("queries").begin_array();
    for (const auto& q : s.evaluation.queries)
      json_query(j, q, s.evaluation.exact_arithmetic, eps_text);
    j.end_array().end_object();
  }
  j.end_array().end_object();
  std::cout << '\n';
}

void print_text(const SolverComparison& result, const std::vector<Ratio>& eps,
                const std::vector<std::string>& eps_text, bool per_query) {
  if (std::any_of(result.solvers.begin(), result.solvers.end(),
                  [](const SolverSummary& s) { return !s.evaluation.exact_arithmetic; }))
    std::cout << "float objectives compared within a relative tolerance of " << result.tolerance
              << (result.tolerance == 0 ? " (exact)" : "") << "\n";
  for (std::size_t i = 0; i < result.solvers.size(); ++i) {
    const auto& s = result.solvers[i];
    std::cout << "solver " << escape_for_terminal(s.name) << " (" << escape_for_terminal(s.file)
              << ")\n";
    if (per_query) print_query_lines(s.evaluation, eps, eps_text);
    std::cout << "  statuses: " << status_counts_text(s.own.statuses, true) << "; " << s.not_solved
              << " solved by the reference only";
    if (s.solved_unreachable)
      std::cout << "; " << s.solved_unreachable
                << " solved where the reference found the goal unreachable";
    std::cout << '\n';
    // Every query the reference solved, once per ε, by why it passes or fails (QueryOutcome).
    for (std::size_t k = 0; k < eps.size(); ++k)
      std::cout << "  ε=" << eps_text[k] << ": " << s.per_epsilon[k].covered << " covered, "
                << s.per_epsilon[k].not_covered << " not covered, " << s.per_epsilon[k].dominated
                << " with vectors the reference dominates while claiming ε = 0, " << s.not_solved
                << " not solved\n";
    const auto count = [](const std::optional<Distribution>& d) { return d ? d->count : 0; };
    std::cout << "  front size over " << count(s.own.front_size)
              << " completed queries: " << distribution_text(s.own.front_size, "", true) << '\n';
    std::cout << "  achieved ε over " << count(s.achieved_epsilon)
              << " queries: " << distribution_text(s.achieved_epsilon, "") << '\n';
    std::cout << "  |S|/|R| over " << count(s.size_ratio)
              << " queries: " << distribution_text(s.size_ratio, "") << '\n';
    std::cout << "  " << to_string(result.runtime) << " runtime over " << count(s.runtime)
              << " queries every solver completed: " << distribution_text(s.runtime, " s");
    if (!s.runtime_recorded)
      std::cout << " (the file records no " << to_string(runtime_statistic(result.runtime)) << ")";
    if (s.runtime)
      std::cout << ", shifted geometric mean (shift " << result.runtime_shift_seconds << " s) "
                << s.runtime->shifted_geometric_mean << " s";
    std::cout << '\n';
    if (s.evaluation.failed) std::cout << "  FAIL\n";
  }
  std::cout << (result.failed ? "FAIL" : "OK") << '\n';
}

// `mosb eval RESULTS [--reference REFS]`: the report's solver table (the paper's Table 5) of an
// experiment's results directory, its instances grouped into benchmarks as the report groups
// them; with references, each solver's ε-coverage per benchmark.
int run_eval_results(const EvalArgs& args) {
  if (args.per_query) throw UsageError("--per-query: not with a results directory");
  pages::ReportOptions options;
  options.runtime = args.options.runtime;
  options.epsilons = parse_epsilons(args.epsilons);
  for (const auto& e : options.epsilons) options.epsilon_labels.push_back(e.to_decimal(18));
  std::vector<GraphReader> instances;
  for (const auto& path : result_instances(args.results))
    instances.push_back(load(path, VerifyLevel::full));
  options.views = result_views(args.results);
  auto solution_paths = experiment_result_files(args.results);
  // Files from outside the experiment (a solver run by hand on its instances) join its table.
  solution_paths.insert(solution_paths.end(), args.solutions.begin(), args.solutions.end());
  const auto solutions = open_verified_all(solution_paths);
  const auto references = args.reference.empty()
                              ? std::vector<SolutionReader>()
                              : open_verified_all(reference_files_of(args.reference, instances));
  auto table = pages::solver_table(
      instances, solutions, references, options,
      args.common_queries ? pages::SolverTable::common_queries : pages::SolverTable::own_queries);
  table.caption = "mosb eval " + args.results +
                  (args.reference.empty() ? std::string() : ", references " + args.reference) +
                  ": " + table.caption;
  if (args.json)
    tables::write_json(std::cout, table);
  else if (args.csv)
    tables::write_csv(std::cout, table);
  else if (args.latex)
    tables::write_latex(std::cout, table);
  else
    tables::write_text(std::cout, table);
  return 0;
}

int run_eval(const EvalArgs& args) {
  if (!args.results.empty()) return run_eval_results(args);
  if (args.common_queries) throw UsageError("--common-queries: with a results directory only");
  if (args.reference.empty() || args.solutions.empty())
    throw UsageError("give a results directory, or --reference FILE and --solutions FILE...");
  if (std::filesystem::is_directory(args.reference) || is_store_url(args.reference))
    throw UsageError("--reference " + args.reference +
                     ": a directory of references, a store or its URL goes with a results "
                     "directory");
  const auto eps = parse_epsilons(args.epsilons);
  std::vector<std::string> eps_text;
  eps_text.reserve(eps.size());
  // 18 digits: a requested ε has at most 18 (parse_epsilon), so its label is exactly what was
  // asked, never two ε rounded to the same 9-digit text.
  for (const auto& e : eps) eps_text.push_back(e.to_decimal(18));
  const auto reference = SolutionReader::open_verified(args.reference);
  std::vector<SolutionReader> solutions;
  solutions.reserve(args.solutions.size());
  for (const auto& file : args.solutions) solutions.push_back(SolutionReader::open_verified(file));
  auto result = compare_solvers(reference, solutions, eps, args.options);
  if (args.json) {
    print_json(result, reference.display_name(), reference.query_count(), eps_text);
  } else if (args.csv || args.latex) {
    // Names as the files give them: the table writers escape them for CSV or LaTeX.
    auto table = args.per_query ? tables::comparison_per_query(result, eps_text, solutions)
                                : tables::comparison_summary(result, eps_text, args.latex);
    std::ostringstream caption;  // a file's caption: the names as given (no terminal escaping)
    caption << "mosb eval: reference " << reference.display_name() << ", "
            << reference.query_count() << " queries, " << to_string(result.runtime)
            << " runtime, float tolerance " << result.tolerance;
    table.caption = caption.str();
    if (args.csv)
      tables::write_csv(std::cout, table);
    else
      tables::write_latex(std::cout, table);
  } else {
    print_text(result, eps, eps_text, args.per_query);
  }
  return result.failed ? 1 : 0;
}

}  // namespace

Command add_eval(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* sub = app.add_subcommand(
      "eval",
      "Compare solvers' solution files with reference fronts: coverage at each ε, achieved "
      "ε, front sizes, runtimes; or an experiment's results per benchmark and solver");
  sub->add_option("RESULTS", args->results,
                  "an experiment's results directory (mosb experiment run -o): per benchmark and "
                  "solver the report's solver table, with --reference REFS/ the ε-coverage")
      ->check(CLI::ExistingDirectory);
  sub->add_option("--reference", args->reference,
                  "the reference solution file, or with RESULTS a directory of references "
                  "(mosb solutions reference -o), a store or a store's URL (its references of "
                  "RESULTS' instances, pulled and checked first)")
      ->check(reference_source());
  sub->add_option("--solutions", args->solutions,
                  "the solvers' solution files (one or more), each compared with the reference; "
                  "with RESULTS, files from outside the experiment that join its table")
      ->expected(1, -1)
      ->check(CLI::ExistingFile);
  sub->add_option("--eps", args->epsilons, "comma-separated ε values")->capture_default_str();
  sub->add_flag("--strict-dominance", args->options.eval.strict_dominance,
                "the paper's literal strict clause (spec/EVALUATION.md §1)");
  sub->add_flag("--per-query", args->per_query,
                "also each query's outcome (text), or one row per solver and query (--csv)");
  sub->add_option("--runtime-shift", args->options.runtime_shift_seconds,
                  "the shift s, in seconds, of the runtimes' shifted geometric mean")
      ->check(non_negative_real())
      ->capture_default_str();
  add_comparison_options(sub, args->options);
  sub->add_flag("--common-queries", args->common_queries,
                "with RESULTS: per benchmark and solver the runtimes over the queries every "
                "solver of the benchmark completed (the paper's comparison table), not over each "
                "solver's own");
  add_json_flag(sub, args->json);
  auto* json = sub->get_option("--json");
  auto* csv = sub->add_flag("--csv", args->csv, "print the summary table as CSV (RFC 4180)");
  auto* latex = sub->add_flag("--latex", args->latex,
                              "print the summary as a LaTeX booktabs tabular, for a paper");
  json->excludes(csv)->excludes(latex);
  csv->excludes(latex);
  latex->excludes(sub->get_option("--per-query"));
  return {sub, [args] { return run_eval(*args); }};
}

}  // namespace mosb::cli
