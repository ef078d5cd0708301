// The solution files behind spec/golden/1.3/solutions/valid/small.sol.mosb (the exact fronts of
// view Small_2: distance u16, time f32, of the golden instance, worked out by hand from its 7
// arcs) and spec/golden/1.4/solutions/valid/objectives.sol.mosb (the same fronts for the objective
// list time,distance, which no view of the instance has: a file bound to its objectives alone)
// and spec/golden/1.5/solutions/valid/reported-runtime.sol.mosb (the fronts of view Small_2 as
// `mosb run` records them: mosb's wall clock and the solver's own runtime), and the content of the
// packed spec/golden/1.6/solutions/ file. Changing any changes its golden file, deliberately.
#pragma once

#include <filesystem>

#include "mosb/graph_reader.hpp"
#include "mosb/solution_file.hpp"

namespace mosb::testing {

inline void write_golden_solutions(const GraphReader& small, const std::filesystem::path& out) {
  SolutionWriter w(small, "Small_2");
  SolverInfo solver;
  solver.name = "hand";
  solver.version = "1";
  solver.parameters["order"] = "lexicographic";
  solver.machine = "pencil and paper";
  w.set_solver(solver);
  w.set_source_tool("mosb 0.1.0");
  // 0 -> 3: 0-2-3 costs (60, 5.25), 0-1-2-3 costs (80, 3.75).
  const std::vector<std::vector<std::uint32_t>> paths0 = {{0, 2, 3}, {0, 1, 2, 3}};
  w.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25, 80, 3.75}, {0.5, 4, 7, 1024},
              paths0);
  // 1 -> 0: 1-2-3-0 (120, 7.5) dominates the direct arc (300, 8).
  const std::vector<std::vector<std::uint32_t>> paths1 = {{1, 2, 3, 0}};
  w.set_query(1, QueryStatus::solved, std::vector<double>{120, 7.5}, {0.25, 5, 9, {}}, paths1);
  // 3 -> 3: timed out (no front, no statistics).
  w.set_query(2, QueryStatus::timeout, {});
  w.write(out);
}

inline void write_golden_objective_solutions(const GraphReader& small,
                                             const std::filesystem::path& out) {
  SolutionWriter w(
      small,
      View{"", {small.objective_index("time"), small.objective_index("distance")}, "default"});
  w.set_source_tool("mosb 0.2.0");
  w.set_query(0, QueryStatus::solved, std::vector<double>{5.25, 60, 3.75, 80});
  w.set_query(1, QueryStatus::solved, std::vector<double>{7.5, 120});
  w.set_query(2, QueryStatus::timeout, {});
  w.write(out);
}

inline void write_golden_reported_runtime_solutions(const GraphReader& small,
                                                    const std::filesystem::path& out) {
  SolutionWriter w(small, "Small_2");
  w.set_source_tool("mosb 0.2.0");
  QueryStatistics first, second;
  first.runtime_seconds = 0.5;  // mosb's wall clock: loading and search
  first.reported_runtime_seconds = 0.125;
  second.runtime_seconds = 0.25;  // a solver that reports no runtime of its own: absent (NaN)
  w.set_query(0, QueryStatus::solved, std::vector<double>{60, 5.25, 80, 3.75}, first);
  w.set_query(1, QueryStatus::solved, std::vector<double>{120, 7.5}, second);
  w.set_query(2, QueryStatus::timeout, {});
  w.write(out);
}

// The content of spec/golden/1.6/solutions/valid/fronts.packed.sol.mosb (packed by mosb pack at
// its default level): a front of 256 vectors, long enough that its columns shrink (distance
// 60, 61, ... under delta-zstd; time 300, 299.5, ... under a shuffle), and the solver's runtime, so
// that it unpacks to 1.5.
inline void write_golden_packable_solutions(const GraphReader& small,
                                            const std::filesystem::path& out) {
  SolutionWriter w(small, "Small_2");
  w.set_source_tool("mosb 0.2.0");
  std::vector<double> front;
  for (int i = 0; i < 256; ++i) {
    front.push_back(60 + i);
    front.push_back(300 - 0.5 * i);
  }
  QueryStatistics first;
  first.runtime_seconds = 0.5;
  first.reported_runtime_seconds = 0.125;
  first.expanded = 4096;
  w.set_query(0, QueryStatus::solved, front, first);
  w.set_query(1, QueryStatus::solved, std::vector<double>{120, 7.5});
  w.set_query(2, QueryStatus::timeout, {});
  w.write(out);
}

}  // namespace mosb::testing
