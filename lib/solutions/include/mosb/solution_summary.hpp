// What is said of a solution file as a whole, in one place for every command that says it: the
// name its solver is shown under, queries per status, and the paper's Table 1 columns (front sizes
// and runtimes over the completed queries; spec/EVALUATION.md §4). `solutions inspect`, `eval`,
// `report` and mosb.plot all take these from here, so they print the same numbers for one file.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mosb/solution_eval.hpp"
#include "mosb/solution_file.hpp"

namespace mosb {

// The name a file's solver is shown under: its solution.solver.name, else the file's name without
// directory and extension ("boa" for results/boa.sol).
std::string solver_name(const SolutionReader& solutions);

// Whose fronts a file holds: for a reference of `solutions reference` (solver "reference" with
// parameter `solvers`), the solvers that gave or agreed with some front (parameter agreed.<i> not
// empty; a solver that completed none of the queries is no part of them), in the order named;
// for any other file its one solver (solver_name).
std::vector<std::string> front_solvers(const SolutionReader& solutions);

// How a table's or figure's caption names the runtime it shows: "wall-clock runtime (mosb's
// measurement)", or "runtime as each solver reported it", followed by the clock where that is
// not the wall clock (reported_clock): "(cpu time)" when every file's is cpu, "(clocks differ:
// emoa cpu; the others wall)" when the files mix them (the others: the most common clock).
std::string runtime_caption(RuntimeSource source, std::span<const SolutionReader* const> files);

// A distribution of non-negative values. The median of an even count is the mean of the two
// middle values. The shifted geometric mean is exp(mean(ln(x + s))) − s, solver papers' usual
// runtime average: one slow query does not dominate it, and the shift s keeps near-zero times
// from doing so either.
struct Distribution {
  std::uint64_t count = 0;
  double median = 0, mean = 0, max = 0;
  double shifted_geometric_mean = 0;  // with a runtime_shift only
  double min = 0;
};

// Values may include +infinity (an achieved ε nothing reaches); the mean is then infinite too.
// nullopt for no values.
std::optional<Distribution> distribution_of(std::vector<double> values,
                                            std::optional<double> runtime_shift = std::nullopt);

// The paper's Table 1 over the files of one benchmark (its instances pooled): front sizes and
// runtimes over the **completed** queries (is_completed: a disconnected query's front size is 0),
// as the paper states its table ("computed over completed queries only").
struct CompletedSummary {
  StatusCounts statuses;                   // of every query of every file
  std::optional<Distribution> front_size;  // nullopt when no query completed
  std::optional<Distribution> runtime;     // runtime_seconds of the completed queries that have it
  // reported_runtime_seconds (the solver's own) of the completed queries that have it
  std::optional<Distribution> reported_runtime;
  // peak_memory_bytes and expanded of the completed queries that have them
  std::optional<Distribution> peak_memory_bytes, expanded;
  const std::optional<Distribution>& runtime_of(RuntimeSource source) const;
};
// O(Q log Q) over the statuses and front offsets; each file must be verified (open_verified).
CompletedSummary summarize_completed(std::span<const SolutionReader* const> files);

struct StatisticSummary {
  Statistic statistic;
  std::uint64_t queries = 0;  // that carry a value
  double total = 0, max = 0;
};

// What `mosb solutions inspect` reports of one file.
struct SolutionSummary {
  CompletedSummary completed;
  std::vector<StatisticSummary> statistics;  // the statistics the file has, in kStatistics order
};

// `solutions` must be verified (open_verified).
SolutionSummary summarize(const SolutionReader& solutions);

}  // namespace mosb
