// Output adapters of `mosb run --output-format` (spec/RUN.md §3.2) for solvers that do not speak
// the solver protocol: each reads what one solver process left for one query through the importers
// of solution_import.hpp, so `mosb run` and `mosb solutions import` read a format the same way.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "mosb/run.hpp"

namespace mosb::converters {

// One output format of `mosb run --output-format` (spec/RUN.md §3.1): its name, what it is, and
// the adapter that reads it.
struct SolverOutputFormat {
  std::string_view name;
  std::string_view description;
  OutputAdapter (*adapter)();  // a function, so the registry is a constant table
};

// Every output format, the default (protocol) first: the registry the command line's choices,
// its help and the run's adapter all come from.
std::span<const SolverOutputFormat> solver_output_formats();
// The format named `name`, or nullptr.
const SolverOutputFormat* find_solver_output_format(std::string_view name);

// The output of a solver that said it did not finish (`status`, because `statement`): never a
// front, whatever else it printed. For every adapter that reads such statements.
ParsedOutput stated_output(QueryStatus status, std::string statement);

// The example-log adapter (apply_example_run_log on stdout, import_front_directory on {fronts}).
ParsedOutput read_example_log_output(const SolverOutputFiles& files);

// The json-log adapter: parse_solver_json_log on {front} (stdout when the template has no
// {front}); one record, whose source and target are the query's.
ParsedOutput read_json_log_output(const SolverOutputFiles& files);

}  // namespace mosb::converters
