// What every `convert` and `generate` command writes, and the one way it writes it: a family's
// subcommand file declares its own options and fills its converter's options; this does the rest.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "mosb/atomic_file.hpp"
#include "mosb/converters/text_input.hpp"
#include "mosb/graph_builder.hpp"
#include "terminal_progress.hpp"

namespace mosb::cli {

// -o FILE, --view (repeatable), --expect-digest and --json.
struct GraphOutput {
  std::string file, expect_digest;
  std::vector<std::string> views;
  bool json = false;
};

// Registers the four options; returns -o's, which the caller makes required (or not, beside
// --suite DIR).
CLI::Option* add_graph_output_options(CLI::App* subcommand, GraphOutput& output);

// Refuses an -o that is one of `inputs` before anything is read; then `convert(progress)` (a
// GraphInput or a StreamedGraph; out of memory anywhere names the first input given), the --view
// specs added, -o written (--expect-digest checked), and reported (report_written). Returns the
// exit code. `convert` takes the terminal's Progress (empty when stderr is no terminal).
template <class Convert>
int write_converted(const GraphOutput& output, const std::vector<std::filesystem::path>& inputs,
                    Convert&& convert) {
  check_output_is_not_input(output.file, inputs);
  TerminalProgress progress;
  const auto work = [&] {
    write_graph(with_views(convert(progress.callback()), output.views), output.file,
                progress.callback(), output.expect_digest);
  };
  const auto named = std::find_if(inputs.begin(), inputs.end(),
                                  [](const std::filesystem::path& p) { return !p.empty(); });
  if (named == inputs.end())
    work();
  else
    converters::naming_input_on_out_of_memory(named->string(), work);
  return report_written(output.file, output.json);
}

}  // namespace mosb::cli
