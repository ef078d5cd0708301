// mosb_cli: the mosb program as a library (KaMinPar's kaminpar-cli is the model). Every
// subcommand's options are registered on one CLI11 app (make_program); main() is the program
// around it. tools/mosb/main.cpp is the executable's main(); tests/cli/program_test.cpp parses
// command lines through make_program in process.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"

namespace CLI {
class App;
}

namespace mosb::cli {

// The command line of `mosb`: the app with every command registered and its help tidied, and
// what to run for each command. `app` is never null; the commands point into it.
struct Program {
  std::unique_ptr<CLI::App> app;
  std::vector<Command> commands;
};
Program make_program();

// The program: parses argv (argc >= 1), runs the chosen command, and reports any error on one
// line of stderr. Returns the exit status: 0 success, 1 failure while running, 2 usage error.
int main(int argc, char** argv);

// Generated from the commands' definitions (`mosb completion bash`, `mosb man`): a bash
// completion script offering each level's subcommands and options, and a man page in roff with
// every command, its options and the exit status. The same program gives the same bytes.
std::string bash_completion(const CLI::App& app);
std::string man_page(const CLI::App& app);

// `mosb completion SHELL` and `mosb man`, which print those of `root`.
Command add_completion(CLI::App& root);
Command add_man(CLI::App& root);

}  // namespace mosb::cli
