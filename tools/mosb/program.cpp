#include "program.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <csignal>
#include <cstdio>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "mosb/atomic_file.hpp"
#include "mosb/error.hpp"
#include "mosb/internal/choices.hpp"
#include "mosb/internal/utf8.hpp"
#include "mosb/version.hpp"

namespace {

constexpr int kRuntimeError = 1;
constexpr int kUsageError = 2;

// "generate grid" for `mosb generate grid ...`: the subcommands given on the command line.
std::string command_path(const CLI::App& app) {
  std::string path;
  for (const CLI::App* current = &app;;) {
    const CLI::App* next = nullptr;
    for (const auto* sub : current->get_subcommands())
      if (sub->count() > 0) next = sub;
    if (!next) return path;
    path += (path.empty() ? "" : " ") + next->get_name();
    current = next;
  }
}

// For a word the deepest command given did not take, the subcommand it may have meant:
// "unknown command 'rnu' (did you mean 'run'?)", else its subcommands ("unknown command 'show'
// (the commands: import, export, ...)"); "" when there is no such word or command.
std::string did_you_mean(const CLI::App& app) {
  const CLI::App* current = &app;
  for (bool deeper = true; deeper;) {
    deeper = false;
    for (const auto* sub : current->get_subcommands())
      if (sub->count() > 0) {
        current = sub;
        deeper = true;
      }
  }
  const auto words = current->remaining();
  if (words.empty() || words.front().starts_with("-")) return {};
  std::vector<std::string> names;
  std::string all;
  for (const auto* sub : current->get_subcommands([](const CLI::App*) { return true; })) {
    all += (all.empty() ? "" : ", ") + sub->get_name();
    names.push_back(sub->get_name());
  }
  if (all.empty()) return {};
  const auto best = mosb::nearest_choice(words.front(), names);
  return "unknown command '" + words.front() + "' (" +
         (best.empty() ? "the commands: " + all : "did you mean '" + best + "'?") + ")";
}

// A usage error is one line: what is wrong, and where to read how it should be.
int usage_error(const CLI::App& app, std::string message) {
  if (auto suggestion = did_you_mean(app); !suggestion.empty()) message = std::move(suggestion);
  for (auto& c : message)  // CLI11 breaks some of its messages into lines
    if (c == '\n' || c == '\r') c = ' ';
  message = mosb::escape_for_terminal(message);  // what the user typed may hold other controls
  const auto path = command_path(app);
  std::cerr << "mosb: " << (path.empty() ? "" : path + ": ") << message << " (see mosb "
            << (path.empty() ? "" : path + " ") << "--help)\n";
  return kUsageError;
}

// An option's value as help shows it: CLI11 joins the value's C++ type and each check's name
// ("UINT:UINT:UINT in [1 - 1024]", "TEXT:DURATION"); the most specific of them is what a user
// types ("UINT in [1 - 1024]", "DURATION"), the rest is noise.
std::string value_name(const std::string& joined) {
  static const std::set<std::string> generic{"TEXT", "UINT", "INT", "FLOAT", "BOOLEAN"};
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t colon = joined.find(':');; colon = joined.find(':', start)) {
    parts.push_back(joined.substr(start, colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  for (std::size_t k = parts.size(); k-- > 0;)  // the last check names it most precisely
    if (!parts[k].empty() && !generic.contains(parts[k])) return parts[k];
  return parts.front();
}

// Every option's value name tidied (value_name), in every subcommand.
void tidy_help(CLI::App& app) {
  for (auto* option : app.get_options()) {
    const auto joined = option->get_type_name();
    if (joined.empty()) continue;
    for (int v = 0;; ++v) {
      try {
        option->get_validator(v)->description("");
      } catch (const CLI::OptionNotFound&) {
        break;
      }
    }
    option->type_name(value_name(joined));
  }
  for (auto* sub : app.get_subcommands([](CLI::App*) { return true; })) tidy_help(*sub);
}

}  // namespace

namespace mosb::cli {

Program make_program() {
  Program p;
  p.app = std::make_unique<CLI::App>(
      "mosb: multi-objective search benchmark instances in a checksummed binary format", "mosb");
  auto& app = *p.app;
  app.set_version_flag("-V,--version", std::string("mosb ") + mosb::kVersion);
  app.footer(
      "Exit status: 0 success; 1 failure while running (bad or damaged input, failed verification, "
      "I/O error); 2 usage error (unknown or missing option, bad option value, no subcommand).");
  app.require_subcommand(1);
  p.commands = {
      add_inspect(app), add_verify(app), add_generate(app),   add_convert(app),    add_queries(app),
      add_stats(app),   add_export(app), add_store(app),      add_suite(app),      add_plot(app),
      add_pack(app),    add_unpack(app), add_solutions(app),  add_eval(app),       add_run(app),
      add_report(app),  add_cache(app),  add_experiment(app), add_completion(app), add_man(app),
  };
  tidy_help(app);
  return p;
}

namespace {

int run_program(int argc, char** argv) {
  const auto program = make_program();
  auto& app = *program.app;
  const auto& commands = program.commands;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == static_cast<int>(CLI::ExitCodes::Success))
      return app.exit(e);  // --help, -V
    return usage_error(app, e.what());
  }
  // Interrupted writes leave no temporary; a file size limit is a write error (EFBIG), reported
  // in one line, rather than a core dump; a temporary left by a killed run is removed and said.
  mosb::remove_temporaries_on_signals();
  std::signal(SIGXFSZ, SIG_IGN);
  mosb::set_stale_temporary_handler([](const std::filesystem::path& path) {
    std::cerr << "mosb: removed " << mosb::escape_for_terminal(path.string())
              << ", left by an earlier run that was killed\n";
  });
  try {
    for (const auto& command : commands)
      if (command.subcommand->parsed()) return command.run();
  } catch (const mosb::cli::UsageError& e) {
    return usage_error(app, e.what());
  } catch (const mosb::Error& e) {
    std::cerr << "mosb: " << mosb::escape_for_terminal(error_text(e)) << '\n';
    return kRuntimeError;
  } catch (const std::exception& e) {
    std::cerr << "mosb: internal error: " << mosb::escape_for_terminal(e.what()) << '\n';
    return kRuntimeError;
  }
  return kRuntimeError;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run_program(argc, argv);
  } catch (...) {  // run_program() reports its own errors; this keeps anything else from aborting
    std::fputs("mosb: internal error while starting\n", stderr);
    return kRuntimeError;
  }
}

}  // namespace mosb::cli
