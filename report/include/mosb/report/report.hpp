// `mosb report`: a suite of instances, and the solvers' solution files for them, as one
// self-contained HTML page (inline SVG and CSS, a short sorting script, no network access) and
// as tables for a paper (spec/EVALUATION.md §7).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "mosb/eval.hpp"
#include "mosb/graph_reader.hpp"
#include "mosb/report/tables.hpp"
#include "mosb/solution_eval.hpp"
#include "mosb/solution_file.hpp"

namespace mosb::pages {

struct ReportOptions {
  std::string title = "mosb report";
  // The queries (0-based positions in each benchmark's query set) whose fronts are drawn; empty:
  // the smallest, the median and the largest solved front of each benchmark.
  std::vector<std::uint64_t> queries;
  std::vector<Ratio> epsilons;              // the ε-coverage's ε values, with a reference
  std::vector<std::string> epsilon_labels;  // as the user wrote them, one per ε
  std::size_t max_points = 1000;            // per front set drawn, past which it is thinned
  // The page's largest size: past it, fronts are drawn with half as many points, down to 50,
  // and past it then make_report throws (ErrorCode::invalid_argument).
  std::size_t max_bytes = 5'000'000;
  std::uint32_t max_map_side = 160;  // squares per map side (plots::MapSquares)
  // Per instance (content digest), the views it is reported by; an instance not listed, by all
  // of its views. An experiment's report lists the views its cells ran (result_views), so that
  // a view of its instances it did not run makes no empty benchmark.
  std::map<std::string, std::set<std::string>> views;
  // The runtime every table and figure shows; nullopt: choose_runtime of the solution files.
  std::optional<RuntimeSource> runtime;
  // The solver the runtime scatter plots set against each other one; empty: the first given.
  std::string baseline;
  // Also the cactus plot and performance profile of every benchmark pooled (each benchmark's
  // own are always drawn): solvers limited to different benchmarks then look unequal.
  bool pooled_figures = false;
  // The instance space in signed ρ; by default |ρ|, as the paper's figure caption has it (its
  // text also quotes signed values: spec/EVALUATION.md §7).
  bool signed_rho = false;
  // The comparison table as the paper prints it: a row per benchmark, each solver's columns
  // under its name (wide past three solvers); by default a row per benchmark and solver.
  bool comparison_by_benchmark = false;
};

// A figure of the page as a document of its own: its kind ("front", "cactus", ...) and its name,
// what --figures calls its file: the kind, then the benchmark (its key) and query it shows
// ("front-grid_2-q3", "cactus-grid_2"; a pooled figure's name is its kind).
struct Figure {
  std::string kind, svg, name;
};

struct Report {
  std::string html;
  std::vector<Figure> figures;  // in page order
  // The page's tables, for --latex and --csv: the suite summary (the paper's Table 1 shape), the
  // instance space (ρ per benchmark), the solvers' comparison (the paper's two-solver table,
  // empty without two solvers) and the ε-coverage per solver (empty without a reference).
  tables::Table suite, instance_space, comparison, coverage;
  // Per benchmark and solver, the paper's Table 5 (solver_table; empty without a solver).
  tables::Table solvers;
  // Per benchmark and objective, the spread (max/min) of the fronts (of the reference, else the
  // first solver) along that objective; per benchmark, sweep and ε the median front size and its
  // reduction against the reference (empty without an approximate solver and a reference).
  tables::Table spread, epsilon_sizes;
  // What the page says about its inputs that a user should also be told where the report is
  // made: each instance given twice (the same content digest), left out and named with its twin.
  std::vector<std::string> notes;
};

// A benchmark is a view (its objectives and query set) over every instance that has it; an
// instance without views is one benchmark of all its objectives. An instance given twice (the
// same content digest, under two paths or one) is counted once, and said in `notes`. Instances must
// be verified in full, solution files with SolutionReader::open_verified. Every solution and
// reference file must be bound to one of the instances (throws ErrorCode::invalid_argument naming
// the file and its instance digest otherwise, or check_bound_to's error), and a solver (or the
// reference) may have one file per instance, view and query set.
Report make_report(std::span<const GraphReader> instances,
                   std::span<const SolutionReader> solutions,
                   std::span<const SolutionReader> references, const ReportOptions& options);

// The page's solver table, the paper's Table 5, alone (`mosb eval RESULTS`): one row per benchmark
// (grouped as the page groups them) and solver, in the order first given: its files, queries,
// solved (completed: solved or shown unreachable), timeouts, memory limits, failures and queries
// not run, the median and max runtime (options.runtime) over its completed queries, and with
// references and options.epsilons the queries evaluated against them and those covered at each
// ε. With SolverTable::common_queries the page's comparison table instead: per benchmark and
// solver, the queries every solver of the benchmark completed and the runtimes over those.
// Binds the files as make_report does, with its errors.
enum class SolverTable { own_queries, common_queries };
tables::Table solver_table(std::span<const GraphReader> instances,
                           std::span<const SolutionReader> solutions,
                           std::span<const SolutionReader> references, const ReportOptions& options,
                           SolverTable kind = SolverTable::own_queries);

}  // namespace mosb::pages
