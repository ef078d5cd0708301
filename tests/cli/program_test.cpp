// mosb_cli in process (tools/mosb/program.hpp): command lines parsed by the program's own app,
// without starting the program; the generated completion script and man page.
#include "program.hpp"

#include <doctest/doctest.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <string>
#include <vector>

using namespace mosb;

namespace {

// Parses `args` (after the program's name) with a fresh program; returns it, parsed.
cli::Program parsed(std::vector<std::string> args) {
  auto program = cli::make_program();
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  program.app->parse(args);
  return program;
}

const cli::Command& chosen(const cli::Program& program) {
  for (const auto& command : program.commands)
    if (command.subcommand->parsed()) return command;
  FAIL("no command chosen");
  return program.commands.front();
}

}  // namespace

TEST_CASE("make_program: options parse in process, and their checks refuse bad values") {
  const std::string instance = std::string(MOSB_SOURCE_DIR) + "/spec/golden/1.0/valid/small.mosb";
  const auto report = parsed({"report", instance, "-o", "r.html", "--comparison-by-benchmark"});
  CHECK(chosen(report).subcommand->get_name() == "report");
  CHECK(parsed({"run", instance, "--view", "V", "--solver", "s", "--time-limit", "90s",
                "--memory-limit", "512m", "-o", "x.sol"})
            .app->get_subcommand("run")
            ->get_option("--time-limit")
            ->as<std::string>() == "90s");
  CHECK_THROWS_AS(parsed({"run", instance, "--time-limit", "5x"}), CLI::ValidationError);
  CHECK_THROWS_AS(parsed({"run", instance, "--memory-limit", "-1G"}), CLI::ValidationError);
  CHECK_THROWS_AS(parsed({"inspect"}), CLI::RequiredError);
  CHECK_THROWS_AS(parsed({"completion", "zsh"}), CLI::ValidationError);
  CHECK_THROWS_AS(parsed({"rnu"}), CLI::ParseError);
  CHECK_THROWS_AS(parsed({}), CLI::RequiredError);  // a subcommand is required
}

TEST_CASE("the completion script and the man page come from the registered commands") {
  const auto program = cli::make_program();
  const auto script = cli::bash_completion(*program.app);
  const auto page = cli::man_page(*program.app);
  for (const auto* sub : program.app->get_subcommands([](const CLI::App*) { return true; })) {
    CAPTURE(sub->get_name());
    CHECK(script.find("\"/" + sub->get_name() + "\") commands=") != std::string::npos);
    CHECK(page.find(".SS \"mosb " + sub->get_name()) != std::string::npos);
  }
  CHECK(script.find("\"/experiment/run\") commands=\"\" options=\"") != std::string::npos);
  CHECK(page.find(".SS \"mosb solutions \\fIcommand\\fR\"") != std::string::npos);
  CHECK(page.find("\\[u03B5]") != std::string::npos);  // ε, spelled for groff
  // The same program, the same bytes.
  const auto again = cli::make_program();
  CHECK(cli::man_page(*again.app) == page);
  CHECK(cli::bash_completion(*again.app) == script);
}

TEST_CASE("error_text: a library error's settings are spelled as the program's flags") {
  const Error error(ErrorCode::invalid_argument,
                    {"give ", setting("shards"), " N or ", setting("queries_per_task"), " K"});
  CHECK(error.message() == "give shards N or queries_per_task K");
  CHECK(cli::error_text(error) == "give --shards N or --queries-per-task K");
  const auto placed = error.with_context("run.json: ");
  CHECK(placed.code() == ErrorCode::invalid_argument);
  CHECK(cli::error_text(placed) == "run.json: give --shards N or --queries-per-task K");
  CHECK(cli::error_text(Error("plain")) == "plain");
  CHECK(cli::flag_of_setting("no_such_setting") == "no_such_setting");
}

namespace {

// Every option name of `app` and of its subcommands, at any depth.
void collect_option_names(const CLI::App& app, std::set<std::string>& names) {
  for (const auto* option : app.get_options())
    for (const auto& name : option->get_lnames()) names.insert("--" + name);
  for (const auto* sub : app.get_subcommands({})) collect_option_names(*sub, names);
}

}  // namespace

TEST_CASE("error_text: every setting the libraries name is a flag of some command") {
  std::set<std::string> flags;
  collect_option_names(*cli::make_program().app, flags);
  const std::regex named(R"re(setting\("([A-Za-z0-9_.]+)"\))re");
  std::set<std::string> settings = {"slurm.account", "slurm.partition"};  // named through a loop
  for (const char* tree : {"lib", "converters"})
    for (const auto& entry :
         std::filesystem::recursive_directory_iterator(std::string(MOSB_SOURCE_DIR) + "/" + tree)) {
      if (entry.path().extension() != ".cpp") continue;
      std::ifstream in(entry.path());
      const std::string text((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
      for (std::sregex_iterator m(text.begin(), text.end(), named), end; m != end; ++m)
        settings.insert((*m)[1].str());
    }
  CHECK(settings.size() > 15);
  for (const auto& name : settings) {
    INFO("setting ", name, " is spelled ", cli::flag_of_setting(name));
    CHECK(flags.count(cli::flag_of_setting(name)) == 1);
  }
}
