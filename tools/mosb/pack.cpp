#include "mosb/pack.hpp"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "json_writer.hpp"
#include "mosb/atomic_file.hpp"

namespace mosb::cli {

namespace {

struct PackArgs {
  std::vector<std::string> inputs;
  std::string output;
  bool in_place = false;
  int level = PackOptions{}.level;
  unsigned threads = 1;
  bool keep_reverse = false;
  bool json = false;
  std::uint64_t max_memory = 0;
};

// The output of each input: -o OUT for one input, the input itself with --in-place.
std::vector<std::string> outputs_of(const PackArgs& a) {
  if (a.in_place == !a.output.empty())
    throw UsageError("give exactly one of -o OUT and --in-place");
  if (!a.output.empty()) {
    if (a.inputs.size() != 1)
      throw UsageError("-o takes one input; give --in-place to rewrite several files");
    check_output_is_not_input(a.output, {a.inputs[0]});
    return {a.output};
  }
  return a.inputs;
}

int run(const PackArgs& a, bool pack) {
  const auto outputs = outputs_of(a);
  JsonWriter* json = nullptr;
  std::unique_ptr<JsonWriter> json_writer;
  if (a.json) {
    json_writer = std::make_unique<JsonWriter>(std::cout);
    json = json_writer.get();
    json->begin_object();
    json->key("files").begin_array();
  }
  for (std::size_t i = 0; i < a.inputs.size(); ++i) {
    const auto before = std::filesystem::file_size(a.inputs[i]);
    // The digest a packed and an unpacked file share.
    const auto digest =
        pack ? pack_file(a.inputs[i], outputs[i],
                         PackOptions{a.level, a.threads, !a.keep_reverse, a.max_memory})
             : unpack_file(a.inputs[i], outputs[i], a.max_memory);
    const auto after = std::filesystem::file_size(outputs[i]);
    if (json) {
      json->begin_object();
      json->key("input").value(a.inputs[i]);
      json->key("output").value(outputs[i]);
      json->key("input_size").value(static_cast<std::uint64_t>(before));
      json->key("output_size").value(static_cast<std::uint64_t>(after));
      json->key("digest").value(digest);
      json->end_object();
    } else {
      std::cout << (pack ? "packed " : "unpacked ") << a.inputs[i] << " -> " << outputs[i] << ": "
                << before << " -> " << after << " bytes, digest " << digest << '\n';
    }
  }
  if (json) {
    json->end_array();
    json->end_object();
  }
  return 0;
}

Command add_pack_command(CLI::App& app, bool pack) {
  auto* sub = app.add_subcommand(
      pack ? "pack" : "unpack",
      pack ? "Compress every section of instances and solution files as zstd frames (table and "
             "digest unchanged)"
           : "Restore the exact bytes of packed instances and solution files");
  auto args = std::make_shared<PackArgs>();
  sub->add_option("FILE", args->inputs, "the .mosb instances or solution files")
      ->required()
      ->check(CLI::ExistingFile);
  auto* output = add_output_option(sub, args->output, "the file to write (one FILE only)");
  sub->add_flag("--in-place", args->in_place, "replace each FILE (atomically)")->excludes(output);
  if (pack) {
    sub->add_option("--level", args->level, "zstd level (fixed, so the bytes are reproducible)")
        ->check(unsigned_integer(std::numeric_limits<int>::max()))
        ->check(CLI::Range(1, 22))
        ->capture_default_str();
    sub->add_option("--threads", args->threads,
                    "sections compressed at once; the output is the same for any value")
        ->check(unsigned_integer(std::numeric_limits<unsigned>::max()))
        ->check(CLI::Range(1U, 256U))
        ->capture_default_str();
    sub->add_flag("--keep-reverse", args->keep_reverse,
                  "store the reverse CSR instead of deriving it when unpacking, so that readers of "
                  "format 1.1 can decode the file");
  }
  add_max_memory_option(sub, args->max_memory);
  add_json_flag(sub, args->json);
  return {sub, [args, pack] { return run(*args, pack); }};
}

}  // namespace

Command add_pack(CLI::App& app) {
  return add_pack_command(app, true);
}
Command add_unpack(CLI::App& app) {
  return add_pack_command(app, false);
}

}  // namespace mosb::cli
