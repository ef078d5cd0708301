// experiment_tasks and task_plan (spec/EXPERIMENT.md §4): the cells of one job array's tasks.
#include <doctest/doctest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "mosb/error.hpp"
#include "mosb/experiment.hpp"

using namespace mosb;

namespace {

ExperimentPlan plan_of(const std::vector<std::uint64_t>& queries) {
  ExperimentPlan plan;
  plan.experiment.name = "x";
  for (std::size_t c = 0; c < queries.size(); ++c) {
    ExperimentCell cell;
    cell.solver = "s";
    cell.instance = "i" + std::to_string(c);
    cell.view = "V";
    cell.queries = queries[c];
    cell.file = "cells/s/i" + std::to_string(c) + ".V.sol";
    plan.cells.push_back(cell);
  }
  return plan;
}

using Tasks = std::vector<std::vector<std::size_t>>;

}  // namespace

TEST_CASE("experiment_tasks: consecutive cells while their queries fit, a large cell alone") {
  const auto plan = plan_of({5, 5, 5, 5, 5});
  CHECK(experiment_tasks(plan, 10) == Tasks{{0, 1}, {2, 3}, {4}});
  CHECK(experiment_tasks(plan, 9) == Tasks{{0}, {1}, {2}, {3}, {4}});
  CHECK(experiment_tasks(plan, 1000) == Tasks{{0, 1, 2, 3, 4}});
  // A cell of more queries than K is a task of its own, neither merged nor split.
  CHECK(experiment_tasks(plan_of({3, 20, 3, 3}), 6) == Tasks{{0}, {1}, {2, 3}});
  CHECK(experiment_tasks(plan_of({20, 1}), 6) == Tasks{{0}, {1}});
  CHECK(experiment_tasks(plan_of({}), 6).empty());
  // Every cell in exactly one task, in plan order.
  const auto tasks = experiment_tasks(plan_of({1, 7, 2, 9, 4, 4, 1, 8}), 8);
  std::vector<std::size_t> all;
  for (const auto& t : tasks) {
    CHECK_FALSE(t.empty());
    all.insert(all.end(), t.begin(), t.end());
  }
  CHECK(all == std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7});
  CHECK_THROWS_AS((void)experiment_tasks(plan, 0), Error);
}

TEST_CASE("task_plan: the same experiment with task i's cells only") {
  const auto plan = plan_of({5, 5, 5});
  const auto tasks = experiment_tasks(plan, 10);
  const auto second = task_plan(plan, tasks, 2);
  CHECK(second.experiment.name == "x");
  REQUIRE(second.cells.size() == 1);
  CHECK(second.cells[0].file == "cells/s/i2.V.sol");
  CHECK(task_plan(plan, tasks, 1).cells.size() == 2);
  CHECK_THROWS_AS((void)task_plan(plan, tasks, 0), Error);
  CHECK_THROWS_AS((void)task_plan(plan, tasks, 3), Error);
}

TEST_CASE("plan_experiment_array: the array's counts and limits, and the tasks it finds again") {
  auto plan = plan_of({5, 5, 20});
  plan.experiment.limits.process.wall_seconds = 60;
  plan.experiment.limits.process.memory_bytes = std::uint64_t{1} << 30;
  SlurmRun run;
  run.directory = "/x/array";
  const auto tasks = plan_experiment_array(run, plan, "/x/exp.toml", 10);
  CHECK(tasks == Tasks{{0, 1}, {2}});
  CHECK(run.kind == kExperimentKind);
  CHECK(run.instance == "/x/exp.toml");
  CHECK(run.shards == 2);
  CHECK(run.queries == 30);
  CHECK(run.largest_shard == 20);
  CHECK(run.time_limit_seconds == 60);
  CHECK(run.memory_limit_bytes == std::uint64_t{1} << 30);
  // Its script: each task runs its cells into a results directory of its own.
  run.mosb = "/opt/mosb";
  run.working_directory = "/x";
  run.run_arguments = {"/x/exp.toml", "--queries-per-task", "10"};
  const std::string script = slurm_script(run);
  CHECK(script.find("#SBATCH --job-name=mosb-experiment\n") != std::string::npos);
  CHECK(script.find("exec /opt/mosb experiment run /x/exp.toml --queries-per-task 10 --task "
                    "\"$shard\"/2 -o /x/array/task-\"$shard\"\n") != std::string::npos);
  CHECK_THROWS_WITH_AS((void)plan_experiment_array(run, plan_of({}), "/x/e.toml", 10),
                       "/x/e.toml: the experiment has no cell", Error);
  // The existing array: found again from its task size, refused once the file plans otherwise.
  run.run_arguments = {"/x/exp.toml", "--queries-per-task", "10", "--jobs", "1"};
  CHECK(experiment_array_tasks(run, plan, "/x/exp.toml") == tasks);
  CHECK(experiment_task_directory(run, 2) == "/x/array/task-2");
  CHECK_THROWS_WITH_AS((void)experiment_array_tasks(run, plan_of({5, 5, 5, 5, 5}), "/x/exp.toml"),
                       doctest::Contains("no longer make the 2 tasks of /x/array"), Error);
  CHECK_THROWS_WITH_AS((void)experiment_array_tasks(run, plan, "/y/exp.toml"),
                       "/x/array/run.json: the job array of /x/exp.toml", Error);
  for (const auto& bad : {std::string("1O"), std::string(""), std::string("-1")}) {
    run.run_arguments = {"/x/exp.toml", "--queries-per-task", bad};
    CHECK_THROWS_WITH_AS((void)experiment_array_tasks(run, plan, "/x/exp.toml"),
                         doctest::Contains("no task size"), Error);
  }
}
