// plan_experiment, run_experiment, experiment_status and merge_experiment_results (spec/
// EXPERIMENT.md) on a small grid, with a stand-in solver that speaks the protocol.
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "mosb/converters/grid_generator.hpp"
#include "mosb/converters/solver_resolver.hpp"
#include "mosb/error.hpp"
#include "mosb/experiment.hpp"
#include "mosb/graph_builder.hpp"
#include "temp_dir.hpp"

using namespace mosb;

namespace {

// An experiment of one solver, a script printing one vector per query, over two grids.
Experiment experiment_in(const testing::TempDir& dir) {
  write_graph(converters::grid_graph({4, 3, 2, 1}), dir / "a.mosb");
  write_graph(converters::grid_graph({5, 3, 2, 2}), dir / "b.mosb");
  const auto solver = dir / "solver.sh";
  std::ofstream(solver) << "#!/bin/sh\necho 1 2\n";
  ::chmod(solver.c_str(), 0755);
  Experiment e;
  e.file = (dir / "x.toml").string();
  e.name = "x";
  e.instances = {dir / "a.mosb", dir / "b.mosb"};
  e.benchmarks = {"Grid_2"};
  e.benchmark_sources = {{}};
  ExperimentSolver s;
  s.name = "s";
  s.spec.solver_template = solver.string() + " {instance} {source} {target}";
  e.solvers.push_back(s);
  return e;
}

ExperimentOptions unsealed() {
  ExperimentOptions options;
  options.seal = Seal::none;  // the seal has tests of its own (tests/cli/test_seal.py)
  return options;
}

}  // namespace

TEST_CASE("an experiment runs its cells once, says their states and merges tasks' results") {
  testing::TempDir dir;
  const auto plan = plan_experiment(experiment_in(dir), converters::solver_resolver());
  REQUIRE(plan.cells.size() == 2);
  CHECK(plan.cells[0].id() == "s/a/Grid_2");
  CHECK(plan.cells[1].file == "cells/s/b.Grid_2.sol");
  const std::atomic<bool> stop{false};
  const auto first = run_experiment(plan, dir / "results", unsealed(), stop);
  CHECK(first.cells == 2);
  CHECK(first.ran == 2);
  CHECK(first.counts[QueryStatus::solved] == plan.cells[0].queries + plan.cells[1].queries);
  const auto states = experiment_status(dir / "results");
  REQUIRE(states.size() == 2);
  for (const auto& s : states) CHECK(s.state == CellState::done);
  // Done cells are not run again.
  const auto again = run_experiment(plan, dir / "results", unsealed(), stop);
  CHECK(again.ran == 0);
  CHECK(again.skipped == 2);
  // The same cells as two array tasks, merged into one results directory.
  const auto tasks = experiment_tasks(plan, 1);
  REQUIRE(tasks.size() == 2);
  std::vector<std::filesystem::path> parts;
  for (std::uint64_t i = 1; i <= tasks.size(); ++i) {
    parts.push_back(dir / ("task-" + std::to_string(i)));
    run_experiment(task_plan(plan, tasks, i), parts.back(), unsealed(), stop);
  }
  CHECK(merge_experiment_results(plan, dir / "merged", parts) == 2);
  for (const auto& s : experiment_status(dir / "merged")) CHECK(s.state == CellState::done);
  CHECK(merge_experiment_results(plan, dir / "merged", parts) == 0);
}

TEST_CASE("a plan names what it refuses: an unknown benchmark, a solver that is not there") {
  testing::TempDir dir;
  auto e = experiment_in(dir);
  e.benchmarks = {"Nope_*"};
  CHECK_THROWS_AS(plan_experiment(e, converters::solver_resolver()), Error);
  e = experiment_in(dir);
  e.solvers[0].spec.solver_template = (dir / "absent").string() + " {instance}";
  CHECK_THROWS_AS(plan_experiment(e, converters::solver_resolver()), Error);
}
