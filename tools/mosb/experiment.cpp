// `mosb experiment run EXP.toml -o RESULTS` and `mosb experiment status RESULTS`
// (spec/EXPERIMENT.md): the file read by converters/experiment, the cells planned and run by
// lib/experiment.
#include "mosb/experiment.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/command_template.hpp"
#include "mosb/converters/experiment_file.hpp"
#include "mosb/converters/solver_resolver.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/slurm.hpp"
#include "mosb/solution_merge.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct ExperimentRunArgs {
  std::string file, output, measurement, isolation;
  unsigned jobs = 1;
  bool json = false;
  // One SLURM job array for the matrix (spec/EXPERIMENT.md §4), and the task an array task runs.
  SlurmArgs slurm;
  std::string task;
  std::vector<std::string> executables;  // --executable NAME=PATH
  // The command line's narrowing of the file: another store, fewer benchmarks, a shorter time.
  std::string store, benchmarks, time_limit;
  bool resume = false;
};

struct ExperimentStatusArgs {
  std::string results;
  bool json = false;
};

// Refusals of the file and of its plan are usage errors: nothing ran.
ExperimentPlan read_plan(const ExperimentRunArgs& a) {
  try {
    auto experiment = converters::read_experiment_file(a.file);
    for (const auto& given : a.executables) {
      const auto eq = given.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == given.size())
        throw UsageError("--executable " + given + ": give NAME=PATH");
      set_solver_executable(experiment, given.substr(0, eq), given.substr(eq + 1));
    }
    if (!a.store.empty()) {
      experiment.store = a.store;
      experiment.instances.clear();
    }
    if (!a.benchmarks.empty()) {
      std::vector<std::string> patterns;
      std::stringstream list(a.benchmarks);
      for (std::string p; std::getline(list, p, ',');)
        if (!p.empty()) patterns.push_back(p);
      restrict_benchmarks(experiment, patterns, "--benchmarks");
    }
    if (!a.time_limit.empty()) set_time_limit(experiment, *parse_duration(a.time_limit));
    for (const auto& [option, value] :
         {std::pair{"--store", &a.store}, std::pair{"--benchmarks", &a.benchmarks},
          std::pair{"--time-limit", &a.time_limit}})
      if (!value->empty())
        experiment.command_line.insert(experiment.command_line.end(), {option, *value});
    for (const auto& given : a.executables)
      experiment.command_line.insert(experiment.command_line.end(), {"--executable", given});
    auto plan = plan_experiment(experiment, converters::solver_resolver());
    for (const auto& note : plan.notes)
      std::cerr << "mosb: note: " << escape_for_terminal(note) << '\n';
    return plan;
  } catch (const Error& e) {
    if (e.code() == ErrorCode::io) throw;
    throw UsageError(error_text(e));
  }
}

// Runs the plan's cells not done into -o (the whole experiment, or one array task's cells).
int run_cells(const ExperimentPlan& plan, const ExperimentRunArgs& a) {
  ExperimentOptions options;
  options.jobs = a.jobs;
  options.measurement = chosen_measurement(a.measurement);
  options.seal = parse_isolation(a.isolation);
  const auto& stop = install_stop_handlers();
  TerminalProgress progress;
  options.progress = [&](const ExperimentProgress& p) { progress.update(p); };
  options.failed = [&](const ExperimentCell& cell, const QueryRecord& r, const Query&) {
    progress.end_line();
    std::cerr << "mosb: " << escape_for_terminal(cell.id()) << ": query " << r.query
              << " failed: " << escape_for_terminal(r.message) << '\n';
  };
  const auto result = run_experiment(plan, a.output, options, stop);
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
    out.key("resumed").value(result.resumed);
    out.key("queries_from_journal").value(result.queries_from_journal);
    out.key("statuses");
    json_status_counts(out, result.counts);
    out.end_object();
    std::cout << '\n';
    return no_query_completed(result.counts, result.failures);
  }
  std::cout << "experiment " << escape_for_terminal(plan.experiment.name) << ": " << result.cells
            << " cells, " << result.ran << " run now";
  if (result.resumed > 0)
    std::cout << " (" << result.resumed << " resumed, " << result.queries_from_journal
              << " queries from their journals)";
  std::cout << ", " << result.skipped << " done before; " << status_counts_text(result.counts, true)
            << "; results in " << escape_for_terminal(a.output) << '\n';
  return no_query_completed(result.counts, result.failures);
}

// --- SLURM: one job array, task i running the cells of experiment_tasks' task i.

// `--task i/N`: what array task i runs, its cells recomputed from the file and checked to be
// those of the array (N tasks of --queries-per-task K).
int run_experiment_task(const ExperimentRunArgs& a) {
  const auto& queries_per_task = a.slurm.queries_per_task;
  if (!queries_per_task) throw UsageError("--task: give --queries-per-task K as well");
  const auto task = parse_shard(a.task);
  if (!task) throw UsageError("--task " + a.task + ": not i/N with 1 <= i <= N");
  const auto plan = read_plan(a);
  const auto tasks = experiment_tasks(plan, *queries_per_task);
  if (tasks.size() != task->count)
    throw UsageError("--task " + a.task + ": the experiment's cells make " +
                     std::to_string(tasks.size()) + " tasks of at most " +
                     std::to_string(*queries_per_task) + " queries, not " +
                     std::to_string(task->count) + " (the experiment changed)");
  return run_cells(task_plan(plan, tasks, task->index), a);
}

int run_experiment_slurm_new(const ExperimentRunArgs& a) {
  const auto& queries_per_task = a.slurm.queries_per_task;
  if (!queries_per_task) throw UsageError("--slurm DIR: give --queries-per-task K");
  const auto plan = read_plan(a);
  SlurmRun run = slurm_run_here(a.slurm.directory);
  plan_experiment_array(run, plan, std::filesystem::absolute(a.file).lexically_normal().string(),
                        *queries_per_task);
  run.jobs = a.jobs;
  run.throttle = a.slurm.throttle;
  run.account = a.slurm.account;
  run.partition = a.slurm.partition;
  run.run_arguments = {run.instance,  "--queries-per-task",   std::to_string(*queries_per_task),
                       "--jobs",      std::to_string(a.jobs), "--measurement",
                       a.measurement, "--isolation",          a.isolation};
  for (const auto& given : a.executables)
    run.run_arguments.insert(run.run_arguments.end(), {"--executable", given});
  for (const auto& [option, value] :
       {std::pair{"--store", &a.store}, std::pair{"--benchmarks", &a.benchmarks},
        std::pair{"--time-limit", &a.time_limit}})
    if (!value->empty()) run.run_arguments.insert(run.run_arguments.end(), {option, *value});
  create_slurm_directory(run);
  std::vector<std::uint64_t> all(run.shards);
  for (std::uint64_t i = 0; i < run.shards; ++i) all[i] = i + 1;
  const auto time = slurm_time_seconds(run);
  std::cout << "wrote " << escape_for_terminal(run.directory) << "/run.sbatch: " << run.shards
            << " tasks of the " << plan.cells.size() << " cells (" << run.queries
            << " queries, at most " << run.largest_shard << " a task), --time "
            << (time ? slurm_time_text(*time) : std::string("(the partition's default)")) << '\n';
  if (a.slurm.submit)
    std::cout << "submitted array job " << submit_shards(run, all) << " (" << run.shards
              << " tasks)\n";
  else
    std::cout << "submit it: " << escape_for_terminal(sbatch_command_text(run, all)) << '\n';
  return 0;
}

void print_task_states(const SlurmStatus& status,
                       const std::vector<std::vector<std::size_t>>& tasks, bool json) {
  std::uint64_t done = 0;
  for (const auto& s : status.shards) done += s.file == ShardFile::done;
  if (json) {
    JsonWriter out(std::cout);
    out.begin_object().key("tasks").value(std::uint64_t{tasks.size()});
    out.key("done").value(done).key("complete").value(done == tasks.size());
    out.key("scheduler").begin_array();
    for (const auto& source : status.sources) out.value(source);
    out.end_array().key("task_states").begin_array();
    for (const auto& s : status.shards)
      out.begin_object()
          .key("task")
          .value(s.index)
          .key("cells")
          .value(std::uint64_t{tasks[s.index - 1].size()})
          .key("queries")
          .value(s.queries)
          .key("recorded")
          .value(s.recorded)
          .key("file")
          .value(to_string(s.file))
          .key("job")
          .value(s.job)
          .key("state")
          .value(s.state)
          .key("problem")
          .value(s.problem)
          .end_object();
    out.end_array().end_object();
    std::cout << '\n';
    return;
  }
  for (const auto& s : status.shards) {
    std::cout << "task " << s.index << "/" << tasks.size() << ": " << to_string(s.file) << ", "
              << s.recorded << " of " << s.queries << " queries";
    if (!s.job.empty()) std::cout << ", " << s.job << " " << escape_for_terminal(s.state);
    if (!s.problem.empty()) std::cout << ": " << escape_for_terminal(s.problem);
    std::cout << '\n';
  }
  std::cout << "summary: " << done << " of " << tasks.size() << " tasks done\n";
}

// `--slurm DIR --status` and `--slurm DIR --resume [--submit]`: the tasks' states; with --resume
// every finished cell merged into -o, and the tasks neither done nor queued resubmitted.
int run_experiment_slurm_existing(const ExperimentRunArgs& a) {
  const auto plan = read_plan(a);
  const SlurmRun run = read_slurm_directory(a.slurm.directory, kExperimentKind);
  const auto tasks = experiment_array_tasks(
      run, plan, std::filesystem::absolute(a.file).lexically_normal().string());
  const auto status = experiment_array_status(run, plan, tasks);
  if (a.slurm.status) {
    print_task_states(status, tasks, a.json);
    return 0;
  }
  std::vector<std::filesystem::path> parts;
  for (std::uint64_t i = 1; i <= run.shards; ++i)
    parts.push_back(experiment_task_directory(run, i));
  const auto merged = merge_experiment_results(plan, a.output, parts);
  const auto resubmit = shards_to_resubmit(status.shards).resubmit;
  std::optional<std::string> job;
  if (a.slurm.submit && !resubmit.empty()) job = submit_shards(run, resubmit);
  if (a.json) {
    JsonWriter out(std::cout);
    out.begin_object().key("results").value(a.output).key("merged").value(merged);
    out.key("resubmit").value(slurm_array_list(resubmit)).key("job").value(job);
    out.end_object();
    std::cout << '\n';
    return 0;
  }
  std::cout << "merged " << merged << " cells into " << escape_for_terminal(a.output) << '\n';
  if (resubmit.empty())
    std::cout << "nothing to resubmit\n";
  else if (job)
    std::cout << "resubmitted tasks " << slurm_array_list(resubmit) << " as array job " << *job
              << '\n';
  else
    std::cout << "resubmit tasks " << slurm_array_list(resubmit) << ": "
              << escape_for_terminal(sbatch_command_text(run, resubmit)) << '\n';
  return 0;
}

int run_experiment_command(const ExperimentRunArgs& a) {
  const auto& slurm = a.slurm;
  if (!a.task.empty()) {
    if (!slurm.directory.empty() || slurm.submit || slurm.status || a.resume)
      throw UsageError("--task: not with --slurm, --submit, --status or --resume");
    return run_experiment_task(a);
  }
  if (!slurm.directory.empty())
    return slurm.status || a.resume ? run_experiment_slurm_existing(a)
                                    : run_experiment_slurm_new(a);
  if (slurm.submit || slurm.status || a.resume || slurm.queries_per_task || slurm.throttle > 0 ||
      !slurm.account.empty() || !slurm.partition.empty())
    throw UsageError(
        "--submit, --status, --resume, --queries-per-task, --throttle, --account and "
        "--partition: only with --slurm DIR");
  return run_cells(read_plan(a), a);
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
      out.key("statuses");
      json_status_counts(out, c.counts);
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
    const auto recorded = recorded_run(a.results);
    std::string command = recorded.file.empty() ? "EXP.toml" : shell_quote(recorded.file);
    for (const auto& argument : recorded.arguments) command += " " + shell_quote(argument);
    std::cout << "to rerun: " << rerun << " cells: `mosb experiment run "
              << escape_for_terminal(command) << " -o " << escape_for_terminal(a.results)
              << "` runs the missing and stopped ones";
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
  add_slurm_options(run, run_args->slurm,
                    {"write one SLURM job array for the whole matrix into DIR (tasks: shards of "
                     "cells); with --status or --resume, the array DIR holds",
                     "with --slurm: consecutive cells packed into tasks of at most K queries",
                     "with --slurm DIR: each task's state"});
  run->add_flag("--resume", run_args->resume,
                "with --slurm DIR: merge the finished cells into -o, resubmit (--submit) the "
                "tasks neither done nor queued");
  run->add_option("--task", run_args->task,
                  "i/N: run array task i's cells only (what the job array's tasks run)");
  run->add_option("--executable", run_args->executables,
                  "NAME=PATH: the executable of the profile solver NAME, over the file's "
                  "(repeatable; one experiment file for every machine)");
  run->add_option("--store", run_args->store,
                  "the store to run on, instead of the file's (a small one on a laptop)")
      ->check(CLI::ExistingDirectory);
  run->add_option("--benchmarks", run_args->benchmarks,
                  "comma-separated patterns: only the cells they match, each must match one "
                  "(the file's per-solver and [[benchmark_limits]] patterns may then match none)");
  run->add_option("--time-limit", run_args->time_limit,
                  "the time limit of every cell, over the file's (60, 60s, 2m, 1h)")
      ->check(duration());
  run->add_option("--jobs,-j", run_args->jobs, "queries of a cell run at the same time")
      ->check(CLI::Range(1u, 1024u));
  add_measurement_option(run, run_args->measurement);
  add_isolation_option(run, run_args->isolation);
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
