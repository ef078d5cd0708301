// `mosb experiment run EXP.toml -o RESULTS` and `mosb experiment status RESULTS`
// (spec/EXPERIMENT.md): the file read by converters/experiment, the cells planned and run by
// lib/experiment.
#include "mosb/experiment.hpp"

#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/converters/experiment_file.hpp"
#include "mosb/converters/solver_output.hpp"
#include "mosb/internal/utf8.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

std::atomic<bool> g_experiment_stop{false};

extern "C" void request_experiment_stop(int) {
  g_experiment_stop.store(true);
}

struct ExperimentRunArgs {
  std::string file, output, measurement = "auto";
  unsigned jobs = 1;
  bool json = false;
};

struct ExperimentStatusArgs {
  std::string results;
  bool json = false;
};

// Refusals of the file and of its plan are usage errors: nothing ran.
ExperimentPlan read_plan(const std::string& file) {
  try {
    return plan_experiment(converters::read_experiment_file(file));
  } catch (const Error& e) {
    if (e.code() == ErrorCode::io) throw;
    throw UsageError(e.what());
  }
}

int run_experiment_command(const ExperimentRunArgs& a) {
  const auto plan = read_plan(a.file);
  ExperimentOptions options;
  options.jobs = a.jobs;
  if (a.measurement != "auto") options.measurement = parse_measurement(a.measurement);
  options.adapter = [](const std::string& name) -> OutputAdapter {
    const auto* format = converters::find_solver_output_format(name);
    return format != nullptr ? format->adapter() : OutputAdapter{};
  };
  struct sigaction action {};
  action.sa_handler = request_experiment_stop;
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
  ::signal(SIGPIPE, SIG_IGN);
  TerminalProgress progress;
  options.progress = [&](const ExperimentProgress& p) { progress.update(p); };
  options.failed = [&](const ExperimentCell& cell, const QueryRecord& r, const Query&) {
    progress.end_line();
    std::cerr << "mosb: " << escape_for_terminal(cell.id()) << ": query " << r.query
              << " failed: " << escape_for_terminal(r.message) << '\n';
  };
  const auto result = run_experiment(plan, a.output, options, g_experiment_stop);
  progress.end_line();
  if (result.interrupted) {
    std::cerr << "mosb: interrupted; finished cells are listed in " << escape_for_terminal(a.output)
              << "/MANIFEST, the running one keeps its journal; "
              << "run the same command again to continue\n";
    return 130;
  }
  if (a.json) {
    JsonWriter out(std::cout);
    out.begin_object();
    out.key("results").value(a.output);
    out.key("cells").value(result.cells);
    out.key("ran").value(result.ran);
    out.key("skipped").value(result.skipped);
    out.key("statuses").begin_object();
    for (const auto status : kQueryStatuses)
      out.key(std::string(to_string(status))).value(result.counts[status]);
    out.end_object();
    out.end_object();
    std::cout << '\n';
    return 0;
  }
  std::cout << "experiment " << escape_for_terminal(plan.experiment.name) << ": " << result.cells
            << " cells, " << result.ran << " run now, " << result.skipped << " done before; "
            << status_counts_text(result.counts, true) << "; results in "
            << escape_for_terminal(a.output) << '\n';
  return 0;
}

int run_experiment_status(const ExperimentStatusArgs& a) {
  const auto cells = experiment_status(a.results);
  std::map<CellState, std::uint64_t> totals;
  for (const auto& c : cells) ++totals[c.state];
  const auto to_rerun = [](const CellStatus& c) {
    return c.state != CellState::done && c.state != CellState::running;
  };
  if (a.json) {
    JsonWriter out(std::cout);
    out.begin_object();
    out.key("cells").begin_array();
    for (const auto& c : cells) {
      out.begin_object();
      out.key("cell").value(c.cell.id());
      out.key("file").value(c.cell.file);
      out.key("state").value(to_string(c.state));
      out.key("queries").value(c.cell.queries);
      out.key("journaled").value(c.journaled);
      out.key("statuses").begin_object();
      for (const auto status : kQueryStatuses)
        out.key(std::string(to_string(status))).value(c.counts[status]);
      out.end_object();
      if (!c.detail.empty()) out.key("detail").value(c.detail);
      out.end_object();
    }
    out.end_array();
    out.key("complete").value(totals[CellState::done] == cells.size());
    out.end_object();
    std::cout << '\n';
    return 0;
  }
  for (const auto& c : cells) {
    std::cout << to_string(c.state) << ' ' << escape_for_terminal(c.cell.id());
    if (c.state == CellState::done || c.state == CellState::failed)
      std::cout << ": " << status_counts_text(c.counts, true);
    if (c.state == CellState::running || c.state == CellState::stopped)
      std::cout << ": " << c.journaled << '/' << c.cell.queries << " queries journaled";
    if (!c.detail.empty()) std::cout << ": " << escape_for_terminal(c.detail);
    std::cout << '\n';
  }
  std::cout << "summary: " << cells.size() << " cells";
  for (const auto& [state, count] : totals) std::cout << ", " << count << ' ' << to_string(state);
  std::cout << '\n';
  const auto rerun = std::count_if(cells.begin(), cells.end(), to_rerun);
  if (rerun > 0) {
    std::cout << "to rerun: " << rerun << " cells: `mosb experiment run EXP.toml -o "
              << escape_for_terminal(a.results) << "` runs the missing and stopped ones";
    if (totals[CellState::failed] + totals[CellState::damaged] > 0)
      std::cout << "; a failed or damaged cell runs again once its file and MANIFEST record are "
                   "removed";
    std::cout << '\n';
  }
  return 0;
}

}  // namespace

Command add_experiment(CLI::App& app) {
  auto* experiment = app.add_subcommand(
      "experiment", "Run solvers x benchmarks from one experiment file (spec/EXPERIMENT.md)");
  auto run_args = std::make_shared<ExperimentRunArgs>();
  auto* run = experiment->add_subcommand(
      "run", "Run every cell (solver x instance x view) not yet done into RESULTS");
  run->add_option("EXP", run_args->file, "the experiment file (TOML)")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("-o,--output", run_args->output, "the results directory")->required();
  run->add_option("--jobs,-j", run_args->jobs, "queries of a cell run at the same time")
      ->check(CLI::Range(1u, 1024u));
  run->add_option("--measurement", run_args->measurement,
                  "how memory is limited and measured (auto, cgroup-v1, rlimit-poll)")
      ->check(CLI::IsMember({"auto", "cgroup-v1", "rlimit-poll"}));
  add_json_flag(run, run_args->json);
  auto status_args = std::make_shared<ExperimentStatusArgs>();
  auto* status = experiment->add_subcommand(
      "status", "Per cell of RESULTS: done, running, stopped, missing, failed or damaged");
  status->add_option("RESULTS", status_args->results, "the results directory")->required();
  add_json_flag(status, status_args->json);
  return group(experiment,
               {{run, [run_args] { return run_experiment_command(*run_args); }},
                {status, [status_args] { return run_experiment_status(*status_args); }}});
}

}  // namespace mosb::cli
