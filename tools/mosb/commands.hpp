// One function per subcommand: each registers its options on the CLI11 app and returns what to run
// when that subcommand is chosen; `run` returns the process exit code.
#pragma once

#include <functional>

namespace CLI {
class App;
}

namespace mosb::cli {

struct Command {
  CLI::App* subcommand;
  std::function<int()> run;
};

Command add_inspect(CLI::App& app);
Command add_verify(CLI::App& app);
Command add_generate(CLI::App& app);
Command add_convert(CLI::App& app);

}  // namespace mosb::cli
