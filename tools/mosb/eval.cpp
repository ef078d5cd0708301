// `mosb eval`: a solver's solution file against a reference solution file (spec/EVALUATION.md §4).
// The evaluation is mosb::evaluate_solutions; this file parses options and prints.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/solution_eval.hpp"

namespace mosb::cli {

namespace {

struct EvalArgs {
  std::string reference, solutions, epsilons = "0.01,0.05,0.1";
  bool strict = false, json = false;
};

std::vector<Ratio> parse_epsilons(const std::string& list) {
  std::vector<Ratio> result;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      result.push_back(parse_epsilon(item));
    } catch (const Error& e) {
      throw UsageError("--eps: '" + item + "': " + e.what());
    }
  }
  if (result.empty()) throw UsageError("--eps: no ε given");
  return result;
}

std::string vector_text(const std::vector<double>& v) {
  std::ostringstream out;
  out << '(';
  for (std::size_t i = 0; i < v.size(); ++i) out << (i ? ", " : "") << v[i];
  out << ')';
  return out.str();
}

void print_text(const SolutionEvaluation& result, const std::vector<Ratio>& eps,
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
      std::cout << ", ε=" << eps_text[k] << ' '
                << (f.coverage[k].covered
                        ? "covered"
                        : "NOT covered (" + std::to_string(f.coverage[k].uncovered) +
                              " uncovered)");
    }
    if (!q.worst_reference_values.empty())
      std::cout << ", worst reference vector " << vector_text(q.worst_reference_values);
    std::cout << (q.failed ? " FAIL" : "") << '\n';
    if (!f.dominated_by_reference.empty() && result.solver_claims_exact)
      std::cout << "query " << q.query << ": SOLVER BUG: " << f.dominated_by_reference.size()
                << " returned vector(s) strictly dominated by the reference (the solver claims "
                   "ε = 0)\n";
  }
  std::cout << "summary: " << result.queries.size() << " queries\n";
  for (std::size_t k = 0; k < eps.size(); ++k)
    std::cout << "  ε=" << eps_text[k] << ": " << result.covered_per_epsilon[k] << " covered\n";
  std::cout << (result.failed ? "FAIL" : "OK") << '\n';
}

void print_json(const SolutionEvaluation& result, const std::vector<std::string>& eps_text) {
  JsonWriter j(std::cout);
  j.begin_object().key("ok").value(!result.failed).key("queries").begin_array();
  for (const auto& q : result.queries) {
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
      j.key("achieved_epsilon").value(achieved_epsilon_text(f, result.exact_arithmetic));
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
  j.end_array().key("summary").begin_array();
  for (std::size_t k = 0; k < eps_text.size(); ++k)
    j.begin_object()
        .key("epsilon")
        .value(eps_text[k])
        .key("covered")
        .value(result.covered_per_epsilon[k])
        .end_object();
  j.end_array().end_object();
  std::cout << '\n';
}

int run_eval(const EvalArgs& args) {
  const auto eps = parse_epsilons(args.epsilons);
  std::vector<std::string> eps_text;
  eps_text.reserve(eps.size());
  // 18 digits: a requested ε has at most 18 (parse_epsilon), so its label is exactly what was
  // asked, never two ε rounded to the same 9-digit text.
  for (const auto& e : eps) eps_text.push_back(e.to_decimal(18));
  const auto reference = SolutionReader::open_verified(args.reference);
  const auto solutions = SolutionReader::open_verified(args.solutions);
  EvalOptions options;
  options.strict_dominance = args.strict;
  const auto result = evaluate_solutions(reference, solutions, eps, options);
  if (args.json)
    print_json(result, eps_text);
  else
    print_text(result, eps, eps_text);
  return result.failed ? 1 : 0;
}

}  // namespace

Command add_eval(CLI::App& app) {
  auto args = std::make_shared<EvalArgs>();
  auto* sub = app.add_subcommand("eval", "Check a solver's solution file against reference fronts");
  sub->add_option("--reference", args->reference, "the reference solution file")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--solutions", args->solutions, "the solver's solution file")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--eps", args->epsilons, "comma-separated ε values")->capture_default_str();
  sub->add_flag("--strict-dominance", args->strict,
                "the paper's literal strict clause (spec/EVALUATION.md §1)");
  add_json_flag(sub, args->json);
  return {sub, [args] { return run_eval(*args); }};
}

}  // namespace mosb::cli
