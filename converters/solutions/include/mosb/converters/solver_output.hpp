// Output adapters of `mosb run --output-format` (spec/RUN.md §3.2) for solvers that do not speak
// the solver protocol: each reads what one solver process left for one query through the importers
// of solution_import.hpp, so `mosb run` and `mosb solutions import` read a format the same way.
#pragma once

#include <optional>
#include <string_view>

#include "mosb/run.hpp"

namespace mosb::converters {

// The adapter of an --output-format name: "protocol" (mosb::read_protocol_output),
// "example-log" (the example solvers' stdout line `start goal front_size seconds expansions` and
// the front file 0.txt they write into the {fronts} directory) or "json-log" (PPA*'s JSON log);
// nullopt for another name.
std::optional<OutputAdapter> solver_output_adapter(std::string_view format);

// The example-log adapter (apply_example_run_log on stdout, import_front_directory on {fronts}).
ParsedOutput read_example_log_output(const SolverOutputFiles& files);

// The json-log adapter: parse_solver_json_log on {front} (stdout when the template has no
// {front}); one record, whose source and target are the query's.
ParsedOutput read_json_log_output(const SolverOutputFiles& files);

}  // namespace mosb::converters
