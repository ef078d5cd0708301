#include <CLI/CLI.hpp>
#include <memory>
#include <optional>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/converters/netmaker_generator.hpp"
#include "mosb/graph_builder.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

namespace {

struct ConvertNetMakerArgs {
  std::string input;
  std::string name;
  std::string output;
  std::string expect_digest;
  std::vector<std::string> views;
  bool json = false;
};

}  // namespace

Command add_convert_netmaker(CLI::App& convert) {
  auto* netmaker = convert.add_subcommand(
      "netmaker",
      "An existing NetMaker graph: 0-based DIMACS-like .gr with one cost column per objective");
  auto args = std::make_shared<ConvertNetMakerArgs>();
  netmaker->add_option("INPUT", args->input, "the .gr file (plain, gzip, bzip2, xz or zstd)")
      ->required()
      ->check(CLI::ExistingFile);
  netmaker->add_option("--name", args->name, "benchmark name (default: the file's base name)");
  add_output_option(netmaker, args->output, "the .mosb file to write")->required();
  add_view_spec_option(netmaker, args->views);
  add_expect_digest_option(netmaker, args->expect_digest);
  add_json_flag(netmaker, args->json);
  return {netmaker, [args] {
            check_output_is_not_input(args->output, {args->input});
            const auto name =
                args->name.empty() ? std::nullopt : std::optional<std::string>(args->name);
            TerminalProgress progress;
            write_graph(with_views(converters::convert_netmaker(args->input, name), args->views),
                        args->output, progress.callback(), args->expect_digest);
            return report_written(args->output, args->json);
          }};
}

}  // namespace mosb::cli
