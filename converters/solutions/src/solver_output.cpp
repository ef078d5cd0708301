#include "mosb/converters/solver_output.hpp"

#include "mosb/converters/solution_import.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/error.hpp"

namespace mosb::converters {

namespace {

// The importers' options for the one query a solver process ran.
SolutionImportOptions one_query_options(const SolverOutputFiles& files) {
  SolutionImportOptions options;
  options.objective_count = files.objectives;
  options.vertex_count = std::uint64_t{1} << 32;  // the endpoints are checked against the query
  options.queries = std::span<const Query>(&files.query, 1);
  return options;
}

}  // namespace

ParsedOutput stated_output(QueryStatus status, std::string statement) {
  ParsedOutput out;
  out.stated_status = status;
  out.stated = std::move(statement);
  return out;
}

ParsedOutput read_example_log_output(const SolverOutputFiles& files) {
  SolutionImportOptions options = one_query_options(files);
  options.status_for_empty = QueryStatus::failed;
  auto results = import_front_directory(files.fronts_dir, options);
  const auto log = read_text_input(files.stdout_path, files.output_bytes);
  apply_example_run_log(log.text, files.stdout_path, options, results);
  if (results.size() == 1 && results.front().status_stated && !is_completed(results.front().status))
    return stated_output(
        results.front().status,
        files.fronts_dir + "/0.txt says status " + std::string(to_string(results.front().status)));
  if (results.size() != 1 || results.front().status == QueryStatus::failed)
    throw Error(files.fronts_dir + ": no front file 0.txt");
  ParsedOutput out;
  out.vectors = results.front().costs.size() / files.objectives;
  out.costs = std::move(results.front().costs);
  out.statistics.expanded = results.front().statistics.expanded;
  out.statistics.runtime_seconds = results.front().statistics.runtime_seconds;
  return out;
}

ParsedOutput read_json_log_output(const SolverOutputFiles& files) {
  SolutionImportOptions options = one_query_options(files);
  options.match = RecordMatch::endpoints;
  const std::string& path = files.front_in_file ? files.front_path : files.stdout_path;
  const auto log = read_text_input(path, files.output_bytes);
  auto results = parse_solver_json_log(log.text, path, options);
  if (results.size() != 1)
    throw Error(path + ": expected one record for the query, found " +
                std::to_string(results.size()));
  const auto& result = results.front();
  if (!is_completed(result.status))
    return stated_output(result.status, path + ": the record says " +
                                            (result.statement.empty()
                                                 ? "status " + std::string(to_string(result.status))
                                                 : result.statement));
  ParsedOutput out;
  out.vectors = result.costs.size() / files.objectives;
  out.costs = result.costs;
  out.statistics.runtime_seconds = result.statistics.runtime_seconds;
  return out;
}

namespace {

constexpr SolverOutputFormat kSolverOutputFormats[] = {
    {"protocol", "the solver protocol (spec/RUN.md section 3)",
     [] { return OutputAdapter(read_protocol_output); }},
    {"example-log",
     "the example solvers' stdout line `start goal front_size seconds expansions` and the front "
     "file 0.txt in {fronts}",
     [] { return OutputAdapter(read_example_log_output); }},
    {"json-log", "PPA*'s JSON log, from {front} (else stdout)",
     [] { return OutputAdapter(read_json_log_output); }},
};

}  // namespace

std::span<const SolverOutputFormat> solver_output_formats() {
  return kSolverOutputFormats;
}

const SolverOutputFormat* find_solver_output_format(std::string_view name) {
  for (const auto& format : kSolverOutputFormats)
    if (format.name == name) return &format;
  return nullptr;
}

}  // namespace mosb::converters
