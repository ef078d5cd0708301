#include <CLI/CLI.hpp>
#include <memory>
#include <optional>

#include "graph_output.hpp"
#include "mosb/converters/netmaker_generator.hpp"

namespace mosb::cli {

namespace {

struct ConvertNetMakerArgs {
  std::string input;
  std::string name;
  GraphOutput output;
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
  add_graph_output_options(netmaker, args->output)->required();
  return {netmaker, [args] {
            const auto name =
                args->name.empty() ? std::nullopt : std::optional<std::string>(args->name);
            return write_converted(args->output, {args->input}, [&](const Progress&) {
              return converters::convert_netmaker(args->input, name);
            });
          }};
}

}  // namespace mosb::cli
