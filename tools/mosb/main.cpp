#include <CLI/CLI.hpp>
#include <csignal>
#include <iostream>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/version.hpp"

int main(int argc, char** argv) {
  CLI::App app{"mosb: multi-objective search benchmark instances in a checksummed binary format"};
  app.set_version_flag("--version", std::string("mosb ") + mosb::kVersion);
  app.require_subcommand(1);
  const std::vector<mosb::cli::Command> commands = {
      mosb::cli::add_inspect(app),
      mosb::cli::add_verify(app),
      mosb::cli::add_generate(app),
      mosb::cli::add_convert(app),
      mosb::cli::add_queries(app),
      mosb::cli::add_stats(app),
      mosb::cli::add_export(app),
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  // Interrupted writes leave no temporary; a file size limit is a write error (EFBIG), reported
  // in one line, rather than a core dump; a temporary left by a killed run is removed and said.
  mosb::remove_temporaries_on_signals();
  std::signal(SIGXFSZ, SIG_IGN);
  mosb::set_stale_temporary_handler([](const std::filesystem::path& path) {
    std::cerr << "mosb: removed " << path.string() << ", left by an earlier run that was killed\n";
  });
  try {
    for (const auto& command : commands)
      if (command.subcommand->parsed()) return command.run();
  } catch (const mosb::Error& e) {
    std::cerr << "mosb: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "mosb: internal error: " << e.what() << '\n';
    return 1;
  }
  return 1;
}
