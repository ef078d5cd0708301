// One function per subcommand: each registers its options on the CLI11 app and returns what to run
// when that subcommand is chosen; `run` returns the process exit code.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace mosb::cli {

struct Command {
  CLI::App* subcommand;
  std::function<int()> run;
};

// A subcommand with one child per family (`convert dimacs`, `generate grid`, ...): runs the chosen one.
Command group(CLI::App* parent, std::vector<Command> children);

// Prints "wrote FILE: n vertices, m arcs, d objectives, digest D" after reopening FILE; returns 0.
int report_written(const std::string& path);

Command add_inspect(CLI::App& app);
Command add_verify(CLI::App& app);
Command add_generate(CLI::App& app);
Command add_convert(CLI::App& app);
Command add_queries(CLI::App& app);  // queries.cpp: `queries import` and `queries generate`
Command add_stats(CLI::App& app);
Command add_export(CLI::App& app);  // export_dimacs.cpp: the `export` group and its children

// Children of `generate`.
Command add_generate_grid(CLI::App& generate);
Command add_generate_netmaker(CLI::App& generate);

// Children of `convert`.
Command add_convert_dimacs(CLI::App& convert);
Command add_convert_netmaker(CLI::App& convert);
Command add_convert_fmi(CLI::App& convert);
Command add_convert_guards(CLI::App& convert);
Command add_convert_movingai(CLI::App& convert);
Command add_convert_roadmap(CLI::App& convert);

}  // namespace mosb::cli
