// Test helper for tests/cli/test_eval.py and test_plot.py: writes a solution file with
// mosb::SolutionWriter. Usage: mosb_test_write_solution INSTANCE VIEW OUT [SOLVER_EPSILON
// [QUERY_SET]] < SPEC, one query a line: "Q STATUS [a,b,... a,b,...]" (vectors of the view's
// objectives, space-separated); a vector may carry its path as "a,b,...@v0/v1/...", and a token
// "t=SECONDS" sets the query's runtime_seconds, "r=SECONDS" its reported_runtime_seconds. The
// solver's name is "test", or the environment's MOSB_TEST_SOLVER_NAME (any bytes: hostile names).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "mosb/graph_reader.hpp"
#include "mosb/solution_file.hpp"

int main(int argc, char** argv) {
  if (argc < 4 || argc > 6) {
    std::cerr << "usage: mosb_test_write_solution INSTANCE VIEW OUT < SPEC\n";
    return 2;
  }
  try {
    const auto instance = mosb::GraphReader::open(argv[1]);
    mosb::SolutionWriter writer(instance, argv[2], argc == 6 ? argv[5] : "");
    if (argc >= 5) {
      mosb::SolverInfo solver;
      const char* name = std::getenv("MOSB_TEST_SOLVER_NAME");
      solver.name = name != nullptr ? name : "test";
      solver.epsilon = argv[4];
      writer.set_solver(solver);
    }
    std::string line;
    while (std::getline(std::cin, line)) {
      std::istringstream in(line);
      std::uint64_t q = 0;
      std::string status_text, vector_text;
      if (!(in >> q >> status_text)) continue;
      const auto status = mosb::parse_query_status(status_text);
      if (!status) throw mosb::Error("unknown status " + status_text);
      std::vector<double> costs;
      std::vector<std::vector<std::uint32_t>> paths;
      mosb::QueryStatistics statistics;
      while (in >> vector_text) {
        if (vector_text.starts_with("t=")) {
          statistics.runtime_seconds = std::stod(vector_text.substr(2));
          continue;
        }
        if (vector_text.starts_with("r=")) {
          statistics.reported_runtime_seconds = std::stod(vector_text.substr(2));
          continue;
        }
        const auto at = vector_text.find('@');
        std::istringstream values(vector_text.substr(0, at));
        std::string value;
        while (std::getline(values, value, ',')) costs.push_back(std::stod(value));
        if (at == std::string::npos) continue;
        std::istringstream vertices(vector_text.substr(at + 1));
        auto& path = paths.emplace_back();
        while (std::getline(vertices, value, '/'))
          path.push_back(static_cast<std::uint32_t>(std::stoul(value)));
      }
      writer.set_query(q, *status, costs, statistics, paths);
    }
    writer.write(argv[3]);
  } catch (const std::exception& e) {
    std::cerr << e.what() << '\n';
    return 1;
  }
  return 0;
}
