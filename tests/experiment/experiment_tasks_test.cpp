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
