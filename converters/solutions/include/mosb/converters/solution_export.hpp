// Writes a solution file back out in the forms `mosb solutions import` reads (spec/SOLUTIONS.md
// §7): per-query front files or a PPA*/BOA*-style JSON log.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "mosb/graph_reader.hpp"
#include "mosb/solution_file.hpp"

namespace mosb::converters {

// One file `<query id>.txt` (ids from `id_base`) per query that was run (every status but not-run)
// in `out_dir` (created when missing): one vector per line, values blank-separated, integers as
// integers and floats in the shortest text that reads back to the stored value; a query without a
// front states its status (`status WORD`, and `exit_status N` when it has one), so that importing
// the directory gives the file back. Returns the number of files.
// The payload is verified first (SolutionReader::verify_payload), and no file is written when one
// of them would replace one of `inputs` (the command's input files: the solution file, the
// instance; check_output_is_not_input). Throws mosb::Error.
std::uint64_t export_front_directory(const SolutionReader& solutions,
                                     const std::filesystem::path& out_dir, unsigned id_base,
                                     const std::vector<std::filesystem::path>& inputs = {});

// `instance` (the file's, check_bound_to) gives the endpoints. A JSON array with one record per
// query that was run, in query order: source and target (from `id_base`); for a solved or
// disconnected query finish_info.solutions[].cost_until_now (empty: disconnected) and
// total_runtime(ms) when the file has the query's runtime; for the others "status" (and
// "exit_status"). Written atomically; refused when `output` is one of `inputs` (as above).
// Returns the number of records.
std::uint64_t export_json_log(const SolutionReader& solutions, const GraphReader& instance,
                              const std::filesystem::path& output, unsigned id_base,
                              const std::vector<std::filesystem::path>& inputs = {});

}  // namespace mosb::converters
