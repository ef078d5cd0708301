// `mosb solutions compare A B`: two solvers' fronts query by query (spec/EVALUATION.md §6), the
// cross-validation of two exact solvers. The comparison is mosb::compare_fronts.
#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/solution_verify.hpp"
#include "mosb/solver_comparison.hpp"

namespace mosb::cli {
namespace {

struct CompareArgs {
  std::string a, b;
  ComparisonOptions options;
  bool per_query = false, json = false;
};

std::string query_line(const QueryAgreement& q, const std::string& a, const std::string& b) {
  std::ostringstream out;
  out << "query " << q.query << ": ";
  if (q.equal) {
    out << "equal (" << to_string(q.a_status) << ')';
  } else if (q.a_status != q.b_status) {
    out << "DIFFERENT: " << to_string(q.a_status) << " in " << a << ", " << to_string(q.b_status)
        << " in " << b;
  } else {
    out << "DIFFERENT fronts: " << cost_vector_text(q.first_difference) << " only in "
        << (q.difference_in_a ? a : b);
  }
  if (q.runtime_ratio) out << ", runtime ratio " << *q.runtime_ratio;
  return out.str();
}

void print_json(const FrontAgreement& r, const CompareArgs& args) {
  JsonWriter j(std::cout);
  j.begin_object().key("a").value(args.a).key("b").value(args.b);
  j.key("tolerance").value(r.tolerance).key("runtime").value(to_string(r.runtime));
  j.key("ok").value(r.different == 0).key("equal").value(r.equal);
  j.key("different").value(r.different).key("runtime_ratio");
  if (r.runtime_ratio)
    j.begin_object()
        .key("count")
        .value(r.runtime_ratio->count)
        .key("median")
        .value(r.runtime_ratio->median)
        .key("mean")
        .value(r.runtime_ratio->mean)
        .key("max")
        .value(r.runtime_ratio->max)
        .end_object();
  else
    j.null();
  j.key("queries").begin_array();
  for (const auto& q : r.queries) {
    j.begin_object().key("query").value(q.query).key("equal").value(q.equal);
    j.key("a_status").value(to_string(q.a_status)).key("b_status").value(to_string(q.b_status));
    if (!q.first_difference.empty()) {
      j.key("first_difference").begin_array();
      for (double v : q.first_difference) j.value(v);
      j.end_array().key("only_in").value(q.difference_in_a ? "a" : "b");
    }
    j.key("runtime_ratio");
    if (q.runtime_ratio)
      j.value(*q.runtime_ratio);
    else
      j.null();
    j.end_object();
  }
  j.end_array().end_object();
  std::cout << '\n';
}

int run_compare(const CompareArgs& args) {
  const auto a = SolutionReader::open_verified(args.a);
  const auto b = SolutionReader::open_verified(args.b);
  const auto result = compare_fronts(a, b, args.options);
  if (args.json) {
    print_json(result, args);
    return result.different ? 1 : 0;
  }
  const auto name_a = escape_for_terminal(args.a), name_b = escape_for_terminal(args.b);
  for (const auto& q : result.queries)
    if (args.per_query || !q.equal) std::cout << query_line(q, name_a, name_b) << '\n';
  std::cout << "summary: " << result.queries.size() << " queries, " << result.equal << " equal, "
            << result.different << " different";
  if (result.runtime_ratio)
    std::cout << "; " << to_string(result.runtime) << " runtime " << name_b << " / " << name_a
              << " over " << result.runtime_ratio->count << " queries: median "
              << result.runtime_ratio->median << ", max " << result.runtime_ratio->max;
  std::cout << '\n' << (result.different ? "FAIL" : "OK") << '\n';
  return result.different ? 1 : 0;
}

}  // namespace

void add_runtime_option(CLI::App* sub, std::optional<RuntimeSource>& runtime) {
  sub->add_option_function<std::string>(
         "--runtime",
         [&runtime](const std::string& name) {
           runtime = *kRuntimeSourceNames.parse(name);  // checked by CLI11
         },
         "the runtime summarised: wall (mosb's wall clock, runtime_seconds) or reported (the "
         "solver's own figure, reported_runtime_seconds); default: reported when every file "
         "records it, else wall")
      ->check(CLI::IsMember(kRuntimeSourceNames.names()));
}

void add_comparison_options(CLI::App* sub, ComparisonOptions& options) {
  sub->add_option("--tolerance", options.tolerance,
                  "relative tolerance within which float objective values are equal (integer "
                  "objectives are exact; 0: exact; spec/EVALUATION.md section 2.1)")
      ->check(CLI::Validator(
          [real = non_negative_real()](std::string& text) -> std::string {
            if (auto problem = real(text); !problem.empty()) return problem;
            return std::stod(text) < 1 ? "" : "'" + text + "' is not below 1";
          },
          "REL", "relative tolerance"))
      ->capture_default_str();
  add_runtime_option(sub, options.runtime);
}

Command add_solutions_compare(CLI::App* solutions) {
  auto args = std::make_shared<CompareArgs>();
  auto* sub = solutions->add_subcommand(
      "compare",
      "Compare two solvers' fronts query by query (equal as sets, or the first "
      "difference) and their runtimes; exit 1 when any query differs");
  sub->add_option("A", args->a, "a solution file")->required()->check(CLI::ExistingFile);
  sub->add_option("B", args->b, "a solution file of the same instance, objectives and query set")
      ->required()
      ->check(CLI::ExistingFile);
  sub->add_flag("--per-query", args->per_query, "a line for every query, not only the differing");
  add_comparison_options(sub, args->options);
  add_json_flag(sub, args->json);
  return {sub, [args] { return run_compare(*args); }};
}

}  // namespace mosb::cli
